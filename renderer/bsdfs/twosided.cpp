// Mitsuba's twosided BSDF (src/bsdfs/twosided.cpp): seen from behind, both directions are mirrored through
// the surface and the back BSDF answers.
#include "twosided.h"

namespace mcval {

namespace {

Vec3f mirrored(const Vec3f &v) { return {v.x, v.y, -v.z}; }

}  // namespace

Color TwoSidedBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    return wi.z > 0.f ? m_front->eval(wi, wo) : m_back->eval(mirrored(wi), mirrored(wo));
}

float TwoSidedBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    return wi.z > 0.f ? m_front->pdf(wi, wo) : m_back->pdf(mirrored(wi), mirrored(wo));
}

BsdfSample TwoSidedBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    if (wi.z > 0.f) return m_front->sample(wi, u);
    BsdfSample s = m_back->sample(mirrored(wi), u);
    s.wo = mirrored(s.wo);
    return s;
}

BsdfSample TwoSidedBsdf::sample(const Vec3f &wi, const Vec2f &u, float uLobe) const {
    if (wi.z > 0.f) return m_front->sample(wi, u, uLobe);
    BsdfSample s = m_back->sample(mirrored(wi), u, uLobe);
    s.wo = mirrored(s.wo);
    return s;
}

}  // namespace mcval
