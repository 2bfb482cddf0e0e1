// Mitsuba's `roughplastic` (isotropic): a diffuse base (RGB) under a rough dielectric coating. The coating's
// microfacets (Beckmann or GGX) reflect by Fresnel's law; light that crosses it scatters diffusely and leaves
// through it again, both crossings weighted by the coating's tabulated transmittance (rough_coating.h).
#pragma once

#include <memory>

#include "bsdf.h"
#include "microfacet.h"
#include "rough_coating.h"

namespace mcval {

class RoughPlasticBsdf final : public Bsdf {
public:
    /// `nonlinear`: the diffuse reflectance darkened by internal scattering (Mitsuba's `nonlinear`).
    RoughPlasticBsdf(const MicrofacetDistribution &distribution, float intIor, float extIor, const Color &diffuse,
                     bool nonlinear);
    /// F D G / (4 cos theta_i) plus rho' / pi cos theta_o T(theta_i) T(theta_o) / eta^2, rho' the reflectance over
    /// its internal reflections; wi and wo above the surface.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    /// Each lobe's density weighted by the probability of choosing it.
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    /// The specular lobe where uLobe is below its probability (Mitsuba's specular sampling weight times 1 - T(wi),
    /// normalised), a microfacet reflection drawn with u; else the cosine hemisphere with u. The weight is the
    /// whole BSDF's value over the whole pdf.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u, float uLobe) const override;
    /// As above, u.x choosing the lobe and, rescaled, drawing the direction with u.y.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    float specularProbability(float cosThetaI) const;

    MicrofacetDistribution m_distribution;
    float m_eta, m_invEta2;
    Color m_diffuse;
    float m_specularWeight;
    bool m_nonlinear;
    std::shared_ptr<const RoughCoating> m_coating;
};

}  // namespace mcval
