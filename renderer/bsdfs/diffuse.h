// Mitsuba's `diffuse`: a Lambertian reflector on the front side, black from behind.
#pragma once

#include "bsdf.h"

namespace mcval {

class DiffuseBsdf final : public Bsdf {
public:
    explicit DiffuseBsdf(const Color &reflectance) : m_reflectance(reflectance) {}
    /// rho / pi cos theta_o where wi and wo are both above the surface, else 0.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    /// The cosine-weighted hemisphere's cos theta_o / pi, where wi and wo are both above the surface.
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    /// Cosine-weighted: the weight is rho.
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    std::optional<Color> lambertianAlbedo(bool front) const override {
        return front ? m_reflectance : Color(0.f, 0.f, 0.f);
    }
    const Color &reflectance() const { return m_reflectance; }

private:
    Color m_reflectance;
};

}  // namespace mcval
