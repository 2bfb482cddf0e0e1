// Mitsuba's `conductor`: a smooth metal, a mirror whose reflectance is the Fresnel reflectance of a conductor of
// complex index eta + i k (one value for every channel here), times specular_reflectance.
#pragma once

#include "bsdf.h"

namespace mcval {

class ConductorBsdf final : public Bsdf {
public:
    ConductorBsdf(float eta, float k, const Color &specular) : m_eta(eta), m_k(k), m_specular(specular) {}
    /// 0: a mirror has no density to evaluate (its lobe is a delta).
    Color eval(const Vec3f &, const Vec3f &) const override { return {0.f, 0.f, 0.f}; }
    float pdf(const Vec3f &, const Vec3f &) const override { return 0.f; }
    /// wo the mirror image of wi about the normal, its weight F(cos theta_i) times the specular reflectance, its
    /// pdf infinite (a delta sample); nothing from below the surface.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    float m_eta, m_k;
    Color m_specular;
};

}  // namespace mcval
