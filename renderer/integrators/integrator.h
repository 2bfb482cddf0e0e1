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

/// Samples of one pixel traced together: lane i is sample `first + i`, its camera ray and, if
/// lanes.found[i], its first hit.
struct SamplePacket {
    int count;        ///< lanes in use, 1..kPacketSize
    uint32_t first;   ///< the sample index of lane 0
    const HitPacket &lanes;
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
        HitPacket lanes;  // lane 0 is this sample; the others hold no ray and no hit
        for (int i = 0; i < kPacketSize; ++i) {
            lanes.setRay(i, i == 0 ? ray : Ray{});
            lanes.clearHit(i);
        }
        if (hit) lanes.setHit(0, *hit);
        Color out;
        LiPacket({1, sampler.index(), lanes}, sampler, &out, counts);
        return out;
    }
    /// Li for every lane of `packet` into out[0..count); the sampler's values for lane i are those of
    /// sample first + i from pair 1 on (pair 0 jittered the camera ray).
    virtual void LiPacket(const SamplePacket &packet, Sampler &sampler, Color *out, RayCounts &counts) const {
        for (int i = 0; i < packet.count; ++i) {
            sampler.startSample(packet.first + static_cast<uint32_t>(i), 1);
            const Hit hit = packet.lanes.hit(i);
            out[i] = Li(packet.lanes.ray(i), packet.lanes.found[i] ? &hit : nullptr, sampler, counts);
        }
    }
};

/// The registered integrator `spec.type` over the given scene; throws SceneError naming the choices otherwise.
std::unique_ptr<Integrator> createIntegrator(const IntegratorSpec &spec, const SceneDescription &scene,
                                             const EmbreeScene &embree);

/// The origin of a ray leaving `hit` in direction d (ray.h's spawnOrigin).
inline Vec3f spawnOrigin(const Hit &hit, const Vec3f &d) { return spawnOrigin(hit.p, hit.ng, hit.offsetFloor, d); }

/// spawnRay as a Ray.
inline Ray spawnRay(const Hit &hit, const Vec3f &d, float tfar) {
    Ray r;
    r.o = spawnOrigin(hit, d);
    r.d = d;
    r.tnear = 0.f;
    r.tfar = tfar;
    return r;
}

/// How much of its length a shadow ray toward a point stops short of it, so that the surface the point
/// lies on (an emitter) does not block it.
constexpr float kShadowShortening = 1e-4f;

/// A shadow ray from `hit` to the point `target`: aimed from its offset origin, not from hit.p. The
/// offset grows with |p| (256 ulps: 5e-4 at 20 from the origin), so a ray aimed from hit.p and moved off
/// would end that far beside the target, past an emitter it should stop short of, whatever the scene's
/// placement; aimed from the origin it ends kShadowShortening of its length before the target.
inline Ray spawnRayTo(const Hit &hit, const Vec3f &target) {
    Ray r;
    r.o = spawnOrigin(hit, target - hit.p);
    const Vec3f toTarget = target - r.o;
    const float dist = norm(toTarget);
    // A target on the origin itself: an empty ray (nothing between), never a NaN direction for Embree.
    const bool apart = dist > 0.f;
    r.d = apart ? toTarget / dist : hit.ng;
    r.tnear = 0.f;
    r.tfar = apart ? dist * (1.f - kShadowShortening) : 0.f;
    return r;
}

}  // namespace mcval
