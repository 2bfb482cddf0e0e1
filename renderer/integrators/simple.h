#pragma once

#include "integrator.h"

namespace mcval {

/// Direct light from point emitters on diffuse surfaces, with shadow rays:
/// L = (rho / pi) * I * max(0, cos) / r^2 * V, summed over the point lights.
class SimpleIntegrator final : public Integrator {
public:
    SimpleIntegrator(const SceneDescription &scene, const EmbreeScene &embree) : m_scene(scene), m_embree(embree) {}
    Color Li(const Ray &ray, const Hit *hit, Sampler &sampler, RayCounts &counts) const override;

private:
    const SceneDescription &m_scene;
    const EmbreeScene &m_embree;
};

}  // namespace mcval
