// Mitsuba's point emitter (src/emitters/point.cpp): sample_direction with pdf 1, weight I / r^2.
#include <cmath>

#include "delta_lights.h"

namespace mcval {

EmitterSample PointEmitter::sample(const Vec3f &ref, const Vec2f &) const {
    EmitterSample s;
    s.p = m_light.position;
    const Vec3f toLight = s.p - ref;
    s.dist = norm(toLight);
    s.d = toLight / s.dist;
    s.pdf = 1.f;
    s.delta = true;
    const float invDist = 1.f / s.dist;
    s.weight = m_light.intensity * (invDist * invDist);
    return s;
}

}  // namespace mcval
