// Nori's `microfacet` (the course's fifth assignment): a diffuse base of albedo kd under a Beckmann specular lobe
// of roughness alpha and weight ks, reflecting by the Fresnel equations of a dielectric (intIOR inside, extIOR
// outside):
//
//   f(wi, wo) = kd / pi + ks D(h) F(wi . h) G1(wi, h) G1(wo, h) / (4 cos theta_i cos theta_o),  h = (wi + wo) / |.|
//
// with Smith's G1 in Walter et al.'s rational fit, as the course has it. Nori derives ks = 1 - max(kd) from a
// coloured kd; here kd and ks are given apart, so that one gray channel (kd's luminance) carries Nori's colour.
#pragma once

#include "bsdf.h"

namespace mcval {

class NoriMicrofacetBsdf final : public Bsdf {
public:
    NoriMicrofacetBsdf(float alpha, float kd, float ks, float intIor, float extIor)
        : m_alpha(alpha), m_kd(kd), m_ks(ks), m_intIor(intIor), m_extIor(extIor) {}
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    /// The mixture of the lobes' densities: ks D(h) cos theta_h / (4 wo . h) + (1 - ks) cos theta_o / pi.
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    /// u.x < ks chooses the specular lobe (h from D(h) cos theta_h, wo the mirror image of wi), else a
    /// cosine-weighted wo; u.x rescaled to [0, 1) draws the direction with u.y.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    /// Smith's masking of v by normals h in Walter et al. 2007's rational fit (0 where v sees their back).
    float smithG1(const Vec3f &v, const Vec3f &h) const;

    float m_alpha, m_kd, m_ks, m_intIor, m_extIor;
};

}  // namespace mcval
