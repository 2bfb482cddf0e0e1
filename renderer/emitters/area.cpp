// Mitsuba's area emitter (src/emitters/area.cpp) for a radiance that does not vary over the shape.
#include "area.h"

namespace mcval {

EmitterSample AreaEmitter::sample(const Vec3f &ref, const Vec2f &u) const {
    const ShapeSample s = m_shape->sample(ref, u);
    EmitterSample e;
    e.d = s.d;
    e.dist = s.dist;
    e.p = s.p;
    e.n = s.ng;
    // Only the front emits: seen from behind (or not at all), nothing arrives.
    const bool seen = dot(s.d, s.ng) < 0.f && s.pdf > 0.f;
    e.pdf = seen ? s.pdf : 0.f;
    e.weight = seen && dot(s.d, s.ns) < 0.f ? m_radiance / s.pdf : Color(0.f, 0.f, 0.f);
    return e;
}

Color AreaEmitter::eval(const EmitterHit &at) const {
    return dot(at.ns, at.d) < 0.f ? m_radiance : Color(0.f, 0.f, 0.f);
}

float AreaEmitter::pdf(const Vec3f &ref, const EmitterHit &at) const {
    return dot(at.d, at.ng) < 0.f ? m_shape->pdf(ref, at) : 0.f;
}

}  // namespace mcval
