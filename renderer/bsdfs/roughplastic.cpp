// Mitsuba's roughplastic (src/bsdfs/roughplastic.cpp), isotropic.
#include "roughplastic.h"

#include <algorithm>

#include "../warp.h"
#include "dielectric.h"

namespace mcval {

RoughPlasticBsdf::RoughPlasticBsdf(const MicrofacetDistribution &distribution, float intIor, float extIor,
                                   const Color &diffuse, bool nonlinear)
    : m_distribution(distribution), m_eta(intIor / extIor), m_invEta2(1.f / (m_eta * m_eta)), m_diffuse(diffuse),
      m_specularWeight(1.f / (meanOf(diffuse) + 1.f)), m_nonlinear(nonlinear),
      m_coating(roughCoating(distribution.type(), distribution.alpha(), m_eta)) {}

float RoughPlasticBsdf::specularProbability(float cosThetaI) const {
    const float t = m_coating->transmittance(cosThetaI);
    const float specular = (1.f - t) * m_specularWeight, diffuse = t * (1.f - m_specularWeight);
    return specular / (specular + diffuse);
}

Color RoughPlasticBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return {0.f, 0.f, 0.f};
    const Vec3f h = normalize(wo + wi);
    const float specular = fresnelDielectric(dot(wi, h), m_eta).reflectance * m_distribution.eval(h) *
                           m_distribution.G(wi, wo, h) / (4.f * wi.z);
    const auto rho = [&](float d) { return d / (1.f - (m_nonlinear ? d : 1.f) * m_coating->internalReflectance); };
    const float diffuse = kInvPi * m_invEta2 * wo.z * m_coating->transmittance(wi.z) * m_coating->transmittance(wo.z);
    return Color(specular + rho(m_diffuse.x) * diffuse, specular + rho(m_diffuse.y) * diffuse,
                 specular + rho(m_diffuse.z) * diffuse);
}

float RoughPlasticBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return 0.f;
    const float p = specularProbability(wi.z);
    const Vec3f h = normalize(wo + wi);
    const float specular = m_distribution.sampleVisible()
                               ? m_distribution.eval(h) * m_distribution.smithG1(wi, h) / (4.f * wi.z)
                               : m_distribution.pdf(wi, h) / (4.f * dot(wo, h));
    return p * specular + (1.f - p) * squareToCosineHemispherePdf(wo);
}

BsdfSample RoughPlasticBsdf::sample(const Vec3f &wi, const Vec2f &u, float uLobe) const {
    BsdfSample s;
    s.wo = Vec3f(0.f, 0.f, 1.f);
    if (!(wi.z > 0.f)) return s;
    Vec3f wo;
    if (uLobe < specularProbability(wi.z)) {
        const Vec3f m = m_distribution.sample(wi, u.x, u.y).m;
        wo = m * (2.f * dot(wi, m)) - wi;
    } else {
        wo = squareToCosineHemisphere(u);
    }
    const float pdf = this->pdf(wi, wo);
    if (!(pdf > 0.f)) return s;  // below the surface, or on no lobe: no sample
    s.wo = wo;
    s.pdf = pdf;
    s.weight = eval(wi, wo) / pdf;
    return s;
}

BsdfSample RoughPlasticBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    if (!(wi.z > 0.f)) return sample(wi, u, 0.f);
    const float p = specularProbability(wi.z);
    // The rest of u.x past the lobe's choice, rescaled to [0, 1), draws the direction with u.y.
    const float ux = u.x < p ? u.x / p : (u.x - p) / (1.f - p);
    return sample(wi, Vec2f(std::min(ux, 0x1.fffffep-1f), u.y), u.x);
}

}  // namespace mcval
