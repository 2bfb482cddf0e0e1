// The delta lights: Mitsuba's point, spot and directional emitters. No ray reaches them, so eval and
// pdf are 0 and sample() is the only way to them (with pdf 1 and delta set, as Mitsuba).
#pragma once

#include "emitter.h"

namespace mcval {

/// Mitsuba's `point`: intensity I (W/sr) at one position; arriving at distance r: I / r^2.
class PointEmitter final : public Emitter {
public:
    explicit PointEmitter(const PointLight &light) : m_light(light) {}
    EmitterKind kind() const override { return EmitterKind::Point; }
    bool isDelta() const override { return true; }
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override;
    Color eval(const EmitterHit &) const override { return {0.f, 0.f, 0.f}; }
    float pdf(const Vec3f &, const EmitterHit &) const override { return 0.f; }

private:
    PointLight m_light;
};

/// Mitsuba's `spot`: a point light along to_world's +z, full intensity within beam_width, falling off
/// linearly in angle to 0 at cutoff_angle (Mitsuba's falloff_curve).
class SpotEmitter final : public Emitter {
public:
    explicit SpotEmitter(const SpotLight &light);
    EmitterKind kind() const override { return EmitterKind::Spot; }
    bool isDelta() const override { return true; }
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override;
    Color eval(const EmitterHit &) const override { return {0.f, 0.f, 0.f}; }
    float pdf(const Vec3f &, const EmitterHit &) const override { return 0.f; }
    /// The falloff in [0, 1] toward the emitter-space direction `local` (not necessarily unit).
    float falloff(const Vec3f &local) const;

private:
    SpotLight m_light;
    Vec3f m_position;
    float m_cutoffRad, m_cosCutoff, m_cosBeam, m_invTransitionWidth, m_uvFactor;
};

/// Mitsuba's `directional`: irradiance E (W/m^2 on a surface facing it) arriving along one direction from
/// infinitely far away.
class DirectionalEmitter final : public Emitter {
public:
    explicit DirectionalEmitter(const DirectionalLight &light);
    EmitterKind kind() const override { return EmitterKind::Directional; }
    bool isDelta() const override { return true; }
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override;
    Color eval(const EmitterHit &) const override { return {0.f, 0.f, 0.f}; }
    float pdf(const Vec3f &, const EmitterHit &) const override { return 0.f; }

private:
    Color m_irradiance;
    Vec3f m_direction;  ///< unit: where the light travels
};

}  // namespace mcval
