// Mitsuba's spot emitter (src/emitters/spot.cpp): a point light whose intensity falls off linearly in
// angle between beam_width and cutoff_angle, as its falloff_curve computes it, times its texture's value
// where the direction meets the cone's image (direction_to_uv).
#include <cmath>

#include "../warp.h"
#include "delta_lights.h"

namespace mcval {

namespace {

float radians(float degrees) { return degrees * (kPi / 180.f); }

}  // namespace

SpotEmitter::SpotEmitter(const SpotLight &light)
    : m_light(light), m_position(light.toWorld.point({0.f, 0.f, 0.f})), m_cutoffRad(radians(light.cutoffAngle)),
      m_cosCutoff(std::cos(m_cutoffRad)), m_cosBeam(std::cos(radians(light.beamWidth))),
      m_invTransitionWidth(1.f / (m_cutoffRad - radians(light.beamWidth))), m_uvFactor(std::tan(m_cutoffRad)) {}

float SpotEmitter::falloff(const Vec3f &local) const {
    const float cosTheta = normalize(local).z;
    const float beam = cosTheta >= m_cosBeam ? 1.f : (m_cutoffRad - std::acos(cosTheta)) * m_invTransitionWidth;
    return cosTheta > m_cosCutoff ? beam : 0.f;
}

EmitterSample SpotEmitter::sample(const Vec3f &ref, const Vec2f &) const {
    EmitterSample s;
    s.p = m_position;
    const Vec3f toLight = s.p - ref;
    s.dist = norm(toLight);
    const float invDist = 1.f / s.dist;
    s.d = toLight * invDist;
    s.pdf = 1.f;
    s.delta = true;
    // The direction leaving the light toward ref, in the light's own space (to_world's inverse).
    const Vec3f local = m_light.toWorld.inverseVector(-s.d);
    const float f = falloff(local);
    if (!(f > 0.f)) return s;
    Color intensity = m_light.intensity;
    if (m_light.texture)
        intensity = intensity * m_light.texture->eval({0.5f + 0.5f * local.x / (local.z * m_uvFactor),
                                                       0.5f + 0.5f * local.y / (local.z * m_uvFactor)});
    s.weight = intensity * (f * (invDist * invDist));
    return s;
}

}  // namespace mcval
