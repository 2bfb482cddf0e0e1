// The mean radiance an integrator estimates along one ray, with its standard error: how the integrator tests
// hold an estimator against a closed form.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>

#include "embree_scene.h"
#include "integrators/registry.h"
#include "scene.h"

namespace mcval {

/// The mean and standard error of n estimates.
struct Estimate {
    double mean = 0.0, error = 0.0;
};

/// n estimates of the radiance along the ray from o along unit d (red channel), by the scene's integrator.
inline Estimate estimate(const SceneDescription &scene, const Vec3f &o, const Vec3f &d, int n) {
    const EmbreeScene embree(scene.meshes, scene.spheres, scene.disks, scene.cylinders, scene.bsdfs);
    const std::unique_ptr<Integrator> integrator = createIntegrator(scene.integrator, scene, embree);
    Ray ray;
    ray.o = o;
    ray.d = d;
    Hit hit;
    const bool found = embree.intersect(ray, hit);
    Sampler sampler(SamplerType::Independent, 1, 0, 0);
    RayCounts counts;
    double sum = 0.0, sum2 = 0.0;
    for (int k = 0; k < n; ++k) {
        sampler.startSample(uint32_t(k), 1);
        const double v = integrator->Li(ray, found ? &hit : nullptr, sampler, counts).x;
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

}  // namespace mcval
