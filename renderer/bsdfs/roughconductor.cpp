// Mitsuba's roughconductor (src/bsdfs/roughconductor.cpp), isotropic.
#include "roughconductor.h"

#include <cmath>

namespace mcval {

float fresnelConductor(float cosThetaI, float eta, float k) {
    // Modified from "Optics" by K. D. Moeller, University Science Books, 1988, as Mitsuba has it.
    const float cos2 = cosThetaI * cosThetaI, sin2 = 1.f - cos2, sin4 = sin2 * sin2;
    const float temp1 = eta * eta - k * k - sin2;
    const float a2pb2 = std::sqrt(std::max(temp1 * temp1 + 4.f * k * k * eta * eta, 0.f));
    const float a = std::sqrt(std::max(0.5f * (a2pb2 + temp1), 0.f));
    const float term1 = a2pb2 + cos2, term2 = 2.f * cosThetaI * a;
    const float rs = (term1 - term2) / (term1 + term2);
    const float term3 = a2pb2 * cos2 + sin4, term4 = term2 * sin2;
    const float rp = rs * (term3 - term4) / (term3 + term4);
    return 0.5f * (rs + rp);
}

Color RoughConductorBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return {0.f, 0.f, 0.f};
    const Vec3f h = normalize(wo + wi);
    const float d = m_distribution.eval(h);
    if (d == 0.f) return {0.f, 0.f, 0.f};
    const float value = d * m_distribution.G(wi, wo, h) / (4.f * wi.z);
    return m_specular * (fresnelConductor(dot(wi, h), m_eta, m_k) * value);
}

float RoughConductorBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    const Vec3f m = normalize(wo + wi);
    if (!(wi.z > 0.f && wo.z > 0.f && dot(wi, m) > 0.f && dot(wo, m) > 0.f)) return 0.f;
    return m_distribution.sampleVisible() ? m_distribution.eval(m) * m_distribution.smithG1(wi, m) / (4.f * wi.z)
                                          : m_distribution.pdf(wi, m) / (4.f * dot(wo, m));
}

BsdfSample RoughConductorBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    BsdfSample s;
    if (!(wi.z > 0.f)) return s;
    const MicrofacetSample ms = m_distribution.sample(wi, u.x, u.y);
    const Vec3f m = ms.m;
    s.wo = m * (2.f * dot(wi, m)) - wi;
    if (!(ms.pdf != 0.f && s.wo.z > 0.f)) {
        s.wo = Vec3f(0.f, 0.f, 1.f);
        return s;
    }
    const float weight = m_distribution.sampleVisible()
                             ? m_distribution.smithG1(s.wo, m)
                             : m_distribution.G(wi, s.wo, m) * dot(wi, m) / (wi.z * m.z);
    s.pdf = ms.pdf / (4.f * dot(s.wo, m));
    s.weight = m_specular * (fresnelConductor(dot(wi, m), m_eta, m_k) * weight);
    return s;
}

}  // namespace mcval
