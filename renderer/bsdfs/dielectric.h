// Mitsuba's `dielectric`: a smooth interface between two indices of refraction (glass in air), reflecting and
// refracting by the Fresnel equations, both from outside and from inside.
#pragma once

#include "bsdf.h"

namespace mcval {

/// Fresnel reflectance of unpolarised light at cos theta_i (negative: from inside) on an interface of relative
/// index eta = int / ext, as Mitsuba's fresnel(): also the cosine of the refracted direction (its sign that of
/// the far side) and eta_ti, the index of wi's side over the far side's. 1 under total internal reflection.
struct Fresnel {
    float reflectance, cosThetaT, etaTi;
};
Fresnel fresnelDielectric(float cosThetaI, float eta);

class DielectricBsdf final : public Bsdf {
public:
    DielectricBsdf(float intIor, float extIor) : m_eta(intIor / extIor) {}
    /// 0: both lobes are deltas.
    Color eval(const Vec3f &, const Vec3f &) const override { return {0.f, 0.f, 0.f}; }
    float pdf(const Vec3f &, const Vec3f &) const override { return 0.f; }
    /// Reflection with the probability R of its Fresnel reflectance, weight 1; else refraction, weight
    /// eta_ti^2 (radiance is compressed by the solid angle it crosses into, as in Mitsuba's radiance mode).
    /// u.x chooses the lobe; both samples have an infinite pdf (delta samples).
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    float m_eta;
};

}  // namespace mcval
