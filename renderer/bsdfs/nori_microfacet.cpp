// Nori's microfacet BRDF (the course's PA5), from its formula.
#include "nori_microfacet.h"

#include <algorithm>
#include <cmath>

#include "../warp.h"
#include "dielectric.h"

namespace mcval {

float NoriMicrofacetBsdf::smithG1(const Vec3f &v, const Vec3f &h) const {
    if (dot(v, h) / v.z <= 0.f) return 0.f;
    const float tanTheta = std::sqrt(std::max(0.f, 1.f - v.z * v.z)) / v.z;
    if (tanTheta == 0.f) return 1.f;
    const float b = 1.f / (m_alpha * tanTheta);
    return b >= 1.6f ? 1.f : (3.535f * b + 2.181f * b * b) / (1.f + 2.276f * b + 2.577f * b * b);
}

Color NoriMicrofacetBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return {0.f, 0.f, 0.f};
    const Vec3f h = normalize(wi + wo);
    // D(h) is Beckmann's density of normals by projected area: squareToBeckmannPdf(h) / cos theta_h.
    const float d = h.z > 0.f ? squareToBeckmannPdf(h, m_alpha) / h.z : 0.f;
    const float fresnel = m_intIor == m_extIor ? 0.f : fresnelDielectric(dot(wi, h), m_intIor / m_extIor).reflectance;
    const float specular = m_ks * d * fresnel * smithG1(wi, h) * smithG1(wo, h) / (4.f * wi.z * wo.z);
    const float v = (m_kd * kInvPi + specular) * wo.z;
    return {v, v, v};
}

float NoriMicrofacetBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return 0.f;
    const Vec3f h = normalize(wi + wo);
    // 1 / (4 wo . h): the Jacobian from the density of h to that of its mirror direction wo.
    const float specular = h.z > 0.f ? squareToBeckmannPdf(h, m_alpha) / (4.f * dot(wo, h)) : 0.f;
    return m_ks * specular + (1.f - m_ks) * squareToCosineHemispherePdf(wo);
}

BsdfSample NoriMicrofacetBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    BsdfSample s;
    s.wo = Vec3f(0.f, 0.f, 1.f);
    if (!(wi.z > 0.f)) return s;
    Vec3f wo;
    if (u.x < m_ks) {
        const float ux = std::min(u.x / m_ks, 0x1.fffffep-1f);
        const Vec3f h = squareToBeckmann(Vec2f(ux, u.y), m_alpha);
        // A normal facing away from wi mirrors it to a direction whose half vector is -h, which the pdf (D is 0
        // below the surface) does not hold: no sample.
        if (!(dot(wi, h) > 0.f)) return s;
        wo = h * (2.f * dot(wi, h)) - wi;
    } else {
        const float ux = std::min((u.x - m_ks) / (1.f - m_ks), 0x1.fffffep-1f);
        wo = squareToCosineHemisphere(Vec2f(ux, u.y));
    }
    const float p = pdf(wi, wo);
    if (!(wo.z > 0.f && p > 0.f)) return s;
    s.wo = wo;
    s.pdf = p;
    s.weight = eval(wi, wo) / p;
    return s;
}

}  // namespace mcval
