// Mitsuba's `roughdielectric` (isotropic): a rough interface between two indices of refraction (Walter et al.
// 2007), its microfacets (Beckmann or GGX) reflecting and refracting by the Fresnel equations, seen from outside
// and from inside, in radiance (a refracted sample carries the solid angle's compression, eta_ti^2).
#pragma once

#include "bsdf.h"
#include "microfacet.h"

namespace mcval {

class RoughDielectricBsdf final : public Bsdf {
public:
    RoughDielectricBsdf(const MicrofacetDistribution &distribution, float intIor, float extIor)
        : m_distribution(distribution), m_eta(intIor / extIor) {}
    /// F D G / (4 |cos theta_i|) where wi and wo are on one side, (1 - F) D G |wi.m wo.m| / |cos theta_i|
    /// / (wi.m + eta wo.m)^2 across (m the generalised half vector, eta that of wo's side over wi's).
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    /// The normal's density (Walter's widened roughness where not from visible normals) times the lobe's
    /// Fresnel probability and the half-vector Jacobian.
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    /// A microfacet normal drawn with u, then reflection on it where uLobe <= F (its Fresnel reflectance) and
    /// refraction through it otherwise (uLobe is Mitsuba's sample1: the C ABI's third uniform).
    BsdfSample sample(const Vec3f &wi, const Vec2f &u, float uLobe) const override;
    /// As above with uLobe hashed from u's bits, where only two uniforms are given: the lobe's probability
    /// depends on the normal drawn from u, so u cannot be rescaled for it.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    /// The distribution normals are drawn from at cos theta_i: from visible normals, the BSDF's own; else its
    /// roughness widened by 1.2 - 0.2 sqrt|cos theta_i| (Walter et al.'s trick, as Mitsuba).
    MicrofacetDistribution samplingDistribution(float cosThetaI) const;

    MicrofacetDistribution m_distribution;
    float m_eta;  ///< int_ior / ext_ior
};

}  // namespace mcval
