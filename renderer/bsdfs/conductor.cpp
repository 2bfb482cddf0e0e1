// Mitsuba's conductor (src/bsdfs/conductor.cpp).
#include "conductor.h"

#include <limits>

#include "roughconductor.h"

namespace mcval {

BsdfSample ConductorBsdf::sample(const Vec3f &wi, const Vec2f &) const {
    BsdfSample s;
    if (!(wi.z > 0.f)) {
        s.wo = Vec3f(0.f, 0.f, 1.f);
        return s;
    }
    s.wo = Vec3f(-wi.x, -wi.y, wi.z);
    s.weight = m_specular * fresnelConductor(wi.z, m_eta, m_k);
    s.pdf = std::numeric_limits<float>::infinity();
    return s;
}

}  // namespace mcval
