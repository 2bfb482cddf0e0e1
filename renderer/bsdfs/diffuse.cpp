// Mitsuba's diffuse BSDF (src/bsdfs/diffuse.cpp).
#include "diffuse.h"

#include "../warp.h"

namespace mcval {

std::shared_ptr<const Bsdf> defaultBsdf() {
    static const std::shared_ptr<const Bsdf> bsdf = std::make_shared<DiffuseBsdf>(Color(0.5f, 0.5f, 0.5f));
    return bsdf;
}

std::shared_ptr<const Bsdf> defaultEmitterBsdf() {
    static const std::shared_ptr<const Bsdf> bsdf = std::make_shared<DiffuseBsdf>(Color(0.f, 0.f, 0.f));
    return bsdf;
}

Color DiffuseBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    if (!(wi.z > 0.f && wo.z > 0.f)) return {0.f, 0.f, 0.f};
    return m_reflectance * (kInvPi * wo.z);
}

float DiffuseBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    return wi.z > 0.f && wo.z > 0.f ? squareToCosineHemispherePdf(wo) : 0.f;
}

BsdfSample DiffuseBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    BsdfSample s;
    s.wo = squareToCosineHemisphere(u);
    s.pdf = squareToCosineHemispherePdf(s.wo);
    const bool active = wi.z > 0.f && s.pdf > 0.f;
    s.weight = active ? m_reflectance : Color(0.f, 0.f, 0.f);
    if (!active) s.pdf = 0.f;
    return s;
}

}  // namespace mcval
