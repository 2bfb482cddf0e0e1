// Mitsuba's plastic (src/bsdfs/plastic.cpp) and fresnel_diffuse_reflectance (include/mitsuba/render/fresnel.h).
#include "plastic.h"

#include <limits>

#include "../warp.h"
#include "dielectric.h"

namespace mcval {

float fresnelDiffuseReflectance(float eta) {
    const float inv = 1.f / eta;
    if (eta < 1.f) return -1.4399f * eta * eta + 0.7099f * eta + 0.6681f + 0.0636f * inv;
    return 0.919317f + inv * (-3.4793f + inv * (6.75335f + inv * (-7.80989f + inv * (4.98554f - 1.36881f * inv))));
}

PlasticBsdf::PlasticBsdf(float intIor, float extIor, const Color &diffuse, bool nonlinear)
    : m_eta(intIor / extIor), m_diffuse(diffuse), m_specularWeight(1.f / (meanOf(diffuse) + 1.f)),
      m_invEta2(1.f / (m_eta * m_eta)), m_fdrInt(fresnelDiffuseReflectance(1.f / m_eta)), m_nonlinear(nonlinear) {}

float PlasticBsdf::specularProbability(float cosThetaI) const {
    const float r = fresnelDielectric(cosThetaI, m_eta).reflectance;
    const float specular = r * m_specularWeight, diffuse = (1.f - r) * (1.f - m_specularWeight);
    return specular / (specular + diffuse);
}

Color PlasticBsdf::diffuseValue(float cosThetaI, float cosThetaO) const {
    const float ti = 1.f - fresnelDielectric(cosThetaI, m_eta).reflectance;
    const float to = 1.f - fresnelDielectric(cosThetaO, m_eta).reflectance;
    const auto rho = [&](float d) { return d / (1.f - (m_nonlinear ? d * m_fdrInt : m_fdrInt)); };
    return Color(rho(m_diffuse.x), rho(m_diffuse.y), rho(m_diffuse.z)) * (kInvPi * cosThetaO * m_invEta2 * ti * to);
}

Color PlasticBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return {0.f, 0.f, 0.f};
    return diffuseValue(wi.z, wo.z);
}

float PlasticBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return 0.f;
    return (1.f - specularProbability(wi.z)) * squareToCosineHemispherePdf(wo);
}

BsdfSample PlasticBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    BsdfSample s;
    s.wo = Vec3f(0.f, 0.f, 1.f);
    if (!(wi.z > 0.f)) return s;
    const float p = specularProbability(wi.z);
    if (u.x < p) {
        s.wo = Vec3f(-wi.x, -wi.y, wi.z);
        const float r = fresnelDielectric(wi.z, m_eta).reflectance;
        s.weight = Color(r / p, r / p, r / p);
        s.pdf = std::numeric_limits<float>::infinity();
        return s;
    }
    // The rest of u.x, rescaled to [0, 1), draws the diffuse direction with u.y.
    const float ux = std::min((u.x - p) / (1.f - p), 0x1.fffffep-1f);
    s.wo = squareToCosineHemisphere(Vec2f(ux, u.y));
    if (!(s.wo.z > 0.f)) {
        s.wo = Vec3f(0.f, 0.f, 1.f);
        return s;
    }
    s.pdf = (1.f - p) * squareToCosineHemispherePdf(s.wo);
    s.weight = diffuseValue(wi.z, s.wo.z) / s.pdf;
    return s;
}

}  // namespace mcval
