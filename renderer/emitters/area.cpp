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
    // Only the front emits, the side the shading normal faces, as eval() has it (and Mitsuba, whose mesh samples
    // carry the interpolated normal): where a mesh's vertex normals face against its winding (Nori's furnace box),
    // light samples find the side that emits. Seen from behind, or not at all, nothing arrives.
    const bool seen = frontFacing(s.d, s.ns) && s.pdf > 0.f;
    e.pdf = seen ? s.pdf : 0.f;
    e.weight = seen ? m_radiance / s.pdf : Color(0.f, 0.f, 0.f);
    return e;
}

Color AreaEmitter::eval(const EmitterHit &at) const {
    return frontFacing(at.d, at.ns) ? m_radiance : Color(0.f, 0.f, 0.f);
}

float AreaEmitter::pdf(const Vec3f &ref, const EmitterHit &at) const {
    // The density sample() draws a direction with: 0 where it draws none (the back).
    return frontFacing(at.d, at.ns) ? m_shape->pdf(ref, at) : 0.f;
}

}  // namespace mcval
