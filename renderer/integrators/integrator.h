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

/// Samples of one pixel traced together: lane i is sample `first + i`, its camera ray rays[i] and,
/// if found[i], its first hit hits[i].
struct SamplePacket {
    int count;        ///< lanes in use, 1..kPacketSize
    uint32_t first;   ///< the sample index of lane 0
    const Ray *rays;
    const Hit *hits;
    const bool *found;
};

/// Estimates the radiance arriving along camera rays. The renderer traces camera rays itself (in
/// packets: the samples of a pixel are coherent) and hands each integrator the first hits.
///
/// An integrator overrides Li (one sample) or LiPacket (a packet, so its own rays can be traced as
/// packets too), or both; each one's default calls the other.
class Integrator {
public:
    virtual ~Integrator() = default;
    /// One sample of the radiance along camera ray `ray`, whose first hit is `hit` (nullptr if it
    /// escaped); the sampler is at its sample, pair 1. Counts the rays it traces beyond the camera ray.
    virtual Color Li(const Ray &ray, const Hit *hit, Sampler &sampler, RayCounts &counts) const {
        const bool found = hit != nullptr;
        Color out;
        LiPacket({1, sampler.index(), &ray, hit, &found}, sampler, &out, counts);
        return out;
    }
    /// Li for every lane of `packet` into out[0..count); the sampler's values for lane i are those of
    /// sample first + i from pair 1 on (pair 0 jittered the camera ray).
    virtual void LiPacket(const SamplePacket &packet, Sampler &sampler, Color *out, RayCounts &counts) const {
        for (int i = 0; i < packet.count; ++i) {
            sampler.startSample(packet.first + static_cast<uint32_t>(i), 1);
            out[i] = Li(packet.rays[i], packet.found[i] ? &packet.hits[i] : nullptr, sampler, counts);
        }
    }
};

/// The registered integrator `spec.type` over the given scene; throws SceneError naming the choices otherwise.
std::unique_ptr<Integrator> createIntegrator(const IntegratorSpec &spec, const SceneDescription &scene,
                                             const EmbreeScene &embree);

/// The origin of a ray leaving `hit` in direction d without re-hitting its surface: moved off the
/// surface, along the geometric normal, by an offset that scales with the position's magnitude and
/// with the size of the scene's smallest shape.
inline Vec3f spawnOrigin(const Hit &hit, const Vec3f &d) {
    const Vec3f side = dot(hit.ng, d) >= 0.f ? hit.ng : -hit.ng;
    return offsetRayOrigin(hit.p, side, hit.offsetFloor);
}

/// spawnRay as a Ray.
inline Ray spawnRay(const Hit &hit, const Vec3f &d, float tfar) {
    Ray r;
    r.o = spawnOrigin(hit, d);
    r.d = d;
    r.tnear = 0.f;
    r.tfar = tfar;
    return r;
}

}  // namespace mcval
