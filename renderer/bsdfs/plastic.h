// Mitsuba's `plastic`: a diffuse base (RGB) under a smooth dielectric coating: the coating reflects by
// Fresnel's law as a mirror, light that enters scatters diffusely and leaves through it again.
#pragma once

#include "bsdf.h"

namespace mcval {

/// Mitsuba's fresnel_diffuse_reflectance: the Fresnel reflectance averaged over a cosine-weighted hemisphere, by
/// the fits of Egan and Hilgeman (eta < 1) and d'Eon and Irving (eta >= 1).
float fresnelDiffuseReflectance(float eta);

class PlasticBsdf final : public Bsdf {
public:
    /// `nonlinear`: the diffuse reflectance darkened by internal scattering (Mitsuba's `nonlinear`).
    PlasticBsdf(float intIor, float extIor, const Color &diffuse, bool nonlinear);
    /// The diffuse part: rho' / pi cos theta_o (1 - F_i)(1 - F_o) / eta^2, rho' the reflectance over its internal
    /// reflections; the specular part is a delta.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    /// The diffuse lobe's probability times the cosine hemisphere's density.
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    /// u.x chooses the lobe, as Mitsuba's specular sampling weight and F_i decide, then (rescaled) with u.y
    /// draws the diffuse direction; a specular sample is a delta sample (infinite pdf).
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    float specularProbability(float cosThetaI) const;
    Color diffuseValue(float cosThetaI, float cosThetaO) const;

    float m_eta;
    Color m_diffuse;
    float m_specularWeight, m_invEta2, m_fdrInt;
    bool m_nonlinear;
};

}  // namespace mcval
