// The integrator interface; integrators are found by name in registry.h.
#pragma once

#include <cstdint>
#include <memory>

#include "../embree_scene.h"
#include "../ray.h"
#include "../sampler.h"
#include "../scene.h"

namespace mcval {

/// Rays traced by one thread, by kind.
struct RayCounts {
    uint64_t camera = 0;
    uint64_t shadow = 0;
    uint64_t total() const { return camera + shadow; }
};

/// Estimates the radiance arriving along a camera ray. The renderer traces camera rays itself
/// (in packets: the samples of a pixel are coherent) and hands each integrator the first hit.
class Integrator {
public:
    virtual ~Integrator() = default;
    /// One sample of the radiance along camera ray `ray`, whose first hit is `hit` (nullptr if it
    /// escaped); counts the rays it traces beyond the camera ray.
    virtual Color Li(const Ray &ray, const Hit *hit, Sampler &sampler, RayCounts &counts) const = 0;
};

/// The registered integrator `spec.type` over the given scene; throws SceneError naming the choices otherwise.
std::unique_ptr<Integrator> createIntegrator(const IntegratorSpec &spec, const SceneDescription &scene,
                                             const EmbreeScene &embree);

/// A ray leaving `hit` in direction d without re-hitting its surface: its origin moves off the
/// surface, along the geometric normal, by an offset that scales with the position's magnitude and
/// with the size of the scene's smallest shape.
inline Ray spawnRay(const Hit &hit, const Vec3f &d, float tfar) {
    const Vec3f side = dot(hit.ng, d) >= 0.f ? hit.ng : -hit.ng;
    Ray r;
    r.o = offsetRayOrigin(hit.p, side, hit.offsetFloor);
    r.d = d;
    r.tnear = 0.f;
    r.tfar = tfar;
    return r;
}

}  // namespace mcval
