// Mitsuba's `roughconductor` (isotropic): a rough metal of microfacets (Beckmann or GGX), reflecting by the
// Fresnel equations of a conductor of complex index eta + i k (one value for every channel here).
#pragma once

#include "bsdf.h"
#include "microfacet.h"

namespace mcval {

/// Fresnel reflectance of unpolarised light at cos theta_i on a conductor of index eta + i k (Mitsuba's
/// fresnel_conductor).
float fresnelConductor(float cosThetaI, float eta, float k);

class RoughConductorBsdf final : public Bsdf {
public:
    RoughConductorBsdf(const MicrofacetDistribution &distribution, float eta, float k, const Color &specular)
        : m_distribution(distribution), m_eta(eta), m_k(k), m_specular(specular) {}
    /// F D G / (4 cos theta_i), wi and wo above the surface.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    /// A microfacet normal from the distribution, wo its mirror image of wi.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    MicrofacetDistribution m_distribution;
    float m_eta, m_k;
    Color m_specular;
};

}  // namespace mcval
