// The emitter interface: what an integrator asks of a light (Mitsuba's Emitter: sample_direction,
// eval, pdf_direction), whatever its kind. Densities are with respect to solid angle at the
// reference point; a delta light (point, spot, directional) has none and reports delta.
#pragma once

#include <cstdint>
#include <limits>

#include "../scene.h"

namespace mcval {

/// The kinds of emitter a scene file holds. `Unmodelled` stands for the types this renderer reads no
/// model of (projector): an integrator that declares it is one whose image they would change.
enum class EmitterKind : uint8_t { Point, Spot, Directional, Constant, Area, Envmap, Unmodelled };

/// A set of emitter kinds: those an integrator reads (IntegratorInfo's SceneUse).
class EmitterKinds {
public:
    constexpr EmitterKinds() = default;
    constexpr EmitterKinds(std::initializer_list<EmitterKind> kinds) {
        for (EmitterKind k : kinds) m_bits |= bit(k);
    }
    /// Every kind, the unmodelled ones included: an integrator that any light of the scene lights.
    static constexpr EmitterKinds all() {
        return {EmitterKind::Point, EmitterKind::Spot, EmitterKind::Directional, EmitterKind::Constant,
                EmitterKind::Area, EmitterKind::Envmap, EmitterKind::Unmodelled};
    }
    constexpr bool has(EmitterKind k) const { return (m_bits & bit(k)) != 0; }
    constexpr bool empty() const { return m_bits == 0; }
    constexpr bool operator==(const EmitterKinds &o) const { return m_bits == o.m_bits; }

private:
    static constexpr uint32_t bit(EmitterKind k) { return 1u << static_cast<uint32_t>(k); }
    uint32_t m_bits = 0;
};

/// A direction toward an emitter from a reference point (Mitsuba's DirectionSample3f).
struct EmitterSample {
    Vec3f d;              ///< unit direction from the reference point toward the emitter
    float dist = 0.f;     ///< distance to the emitter's point; infinite for constant and directional
    Vec3f p;              ///< the point on the emitter (area, point, spot)
    Vec3f n;              ///< the emitter's unit normal at p, on its front (area); zero for the others
    Color weight;         ///< what arrives at the reference point over pdf (0 where nothing does)
    float pdf = 0.f;      ///< density of d by solid angle; 1 for a delta light
    bool delta = false;   ///< a point, spot or directional light: no other strategy can find it
};

/// Where a ray reached an emitter, for eval and pdf: the point, the emitter's front-facing normals
/// there and the ray (its unit direction d, from the reference point, and its length).
struct EmitterHit {
    Vec3f p;
    Vec3f ng;             ///< geometric normal, on the front (Hit::ng): the pdf's cosine
    Vec3f ns;             ///< shading normal (Hit::ns): which side emits, as Mitsuba's cos_theta(si.wi) > 0
    Vec3f d;              ///< unit direction of the ray that reached it
    float dist = std::numeric_limits<float>::infinity();  ///< its length; infinite for an escaped ray
};

class Emitter {
public:
    virtual ~Emitter() = default;
    virtual EmitterKind kind() const = 0;
    /// Whether the light sits at a point or along a direction (no ray hits it; pdf() is 0).
    virtual bool isDelta() const = 0;
    /// A direction toward the emitter from `ref`, drawn with the uniforms u in [0, 1)^2.
    virtual EmitterSample sample(const Vec3f &ref, const Vec2f &u) const = 0;
    /// The radiance leaving the emitter at `at` toward -at.d (0 for delta lights: no ray reaches them).
    virtual Color eval(const EmitterHit &at) const = 0;
    /// The density by solid angle with which sample(ref, .) draws the direction of `at` (0 for delta lights).
    virtual float pdf(const Vec3f &ref, const EmitterHit &at) const = 0;
};

}  // namespace mcval
