// Mitsuba's constant emitter (src/emitters/constant.cpp): radiance L from every direction, sampled
// uniformly over the sphere (pdf 1 / 4 pi), as Mitsuba samples it.
#include "constant.h"

#include <limits>

#include "../warp.h"

namespace mcval {

EmitterSample ConstantEmitter::sample(const Vec3f &, const Vec2f &u) const {
    EmitterSample s;
    s.d = squareToUniformSphere(u);
    s.dist = std::numeric_limits<float>::infinity();
    s.n = -s.d;
    s.pdf = squareToUniformSpherePdf(s.d);
    s.weight = m_radiance / s.pdf;
    return s;
}

float ConstantEmitter::pdf(const Vec3f &, const EmitterHit &at) const { return squareToUniformSpherePdf(at.d); }

}  // namespace mcval
