// Mitsuba's dielectric (src/bsdfs/dielectric.cpp) and its fresnel() (include/mitsuba/render/fresnel.h).
#include "dielectric.h"

#include <cmath>
#include <limits>

namespace mcval {

Fresnel fresnelDielectric(float cosThetaI, float eta) {
    const bool outside = cosThetaI >= 0.f;
    const float etaIt = outside ? eta : 1.f / eta, etaTi = outside ? 1.f / eta : eta;
    const float cosThetaTSqr = 1.f - (1.f - cosThetaI * cosThetaI) * (etaTi * etaTi);
    const float cosI = std::abs(cosThetaI), cosT = std::sqrt(std::max(cosThetaTSqr, 0.f));
    float r;
    if (eta == 1.f) {
        r = 0.f;
    } else if (cosI == 0.f) {
        r = 1.f;
    } else {
        const float as = (cosI - etaIt * cosT) / (cosI + etaIt * cosT);
        const float ap = (cosT - etaIt * cosI) / (cosT + etaIt * cosI);
        r = 0.5f * (as * as + ap * ap);
    }
    return {r, outside ? -cosT : cosT, etaTi};
}

BsdfSample DielectricBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    BsdfSample s;
    const Fresnel f = fresnelDielectric(wi.z, m_eta);
    s.pdf = std::numeric_limits<float>::infinity();
    if (u.x <= f.reflectance) {
        s.wo = Vec3f(-wi.x, -wi.y, wi.z);
        s.weight = Color(1.f, 1.f, 1.f);
    } else {
        s.wo = Vec3f(-f.etaTi * wi.x, -f.etaTi * wi.y, f.cosThetaT);
        const float factor = f.etaTi * f.etaTi;
        s.weight = Color(factor, factor, factor);
        s.eta = 1.f / f.etaTi;
    }
    return s;
}

}  // namespace mcval
