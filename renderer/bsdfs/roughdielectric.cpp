// Mitsuba's roughdielectric (src/bsdfs/roughdielectric.cpp), isotropic, in radiance mode.
#include "roughdielectric.h"

#include <cmath>
#include <cstdint>
#include <cstring>

#include "dielectric.h"

namespace mcval {

namespace {

float sqr(float x) { return x * x; }

/// wi and wo's generalised half vector m, turned to the macro-surface's side: along wi + wo where they are on
/// one side (a reflection), along wi + eta wo across, eta the index of wo's side over wi's.
struct HalfVector {
    Vec3f m;
    float eta = 1.f;   ///< wo's side over wi's (1 for a reflection)
    bool reflect = false;
    bool valid = false;  ///< false where wi is in the tangent plane or wi + eta wo vanishes
};

HalfVector halfVector(const Vec3f &wi, const Vec3f &wo, float eta) {
    HalfVector h;
    if (wi.z == 0.f) return h;  // grazing: nothing, as Mitsuba
    h.reflect = wi.z * wo.z > 0.f;
    h.eta = h.reflect ? 1.f : (wi.z > 0.f ? eta : 1.f / eta);
    const Vec3f v = wi + wo * h.eta;
    const float length = norm(v);
    if (!(length > 0.f)) return h;
    h.m = v / length;
    if (h.m.z < 0.f) h.m = -h.m;
    h.valid = true;
    return h;
}

/// The density of wo by solid angle per density of m: 1 / (4 wo.m) for a reflection, eta^2 |wo.m| / (wi.m +
/// eta wo.m)^2 across.
float halfVectorJacobian(const Vec3f &wi, const Vec3f &wo, const Vec3f &m, bool reflect, float eta) {
    const float woM = dot(wo, m);
    return reflect ? 1.f / (4.f * std::abs(woM)) : eta * eta * std::abs(woM) / sqr(dot(wi, m) + eta * woM);
}

/// A uniform in [0, 1) from u's 64 bits (a 32-bit mixing finaliser: every bit of u moves every bit of it).
float hashedUniform(const Vec2f &u) {
    uint32_t a, b;
    std::memcpy(&a, &u.x, sizeof a);
    std::memcpy(&b, &u.y, sizeof b);
    uint32_t h = a * 0x9e3779b9u ^ (b + 0x7f4a7c15u + (a << 6) + (a >> 2));
    h ^= h >> 16, h *= 0x85ebca6bu, h ^= h >> 13, h *= 0xc2b2ae35u, h ^= h >> 16;
    return static_cast<float>(h >> 8) * 0x1p-24f;
}

}  // namespace

MicrofacetDistribution RoughDielectricBsdf::samplingDistribution(float cosThetaI) const {
    if (m_distribution.sampleVisible()) return m_distribution;
    const float scale = 1.2f - 0.2f * std::sqrt(std::abs(cosThetaI));
    return MicrofacetDistribution(m_distribution.type(), m_distribution.alpha() * scale, false);
}

Color RoughDielectricBsdf::eval(const Vec3f &wi, const Vec3f &wo) const {
    const HalfVector h = halfVector(wi, wo, m_eta);
    if (!h.valid) return {0.f, 0.f, 0.f};
    const Vec3f &m = h.m;
    const float d = m_distribution.eval(m);
    const float g = m_distribution.G(wi, wo, m);  // 0 where wi or wo sees a microfacet's back
    if (d == 0.f || g == 0.f) return {0.f, 0.f, 0.f};
    const float wiM = dot(wi, m), woM = dot(wo, m);
    const float f = fresnelDielectric(wiM, m_eta).reflectance;
    float value;
    if (h.reflect) {
        value = f * d * g / (4.f * std::abs(wi.z));
    } else {
        // Radiance's 1 / eta^2 (the solid angle's compression) cancels the half-vector Jacobian's eta^2.
        value = std::abs((1.f - f) * d * g * wiM * woM / (wi.z * sqr(wiM + h.eta * woM)));
    }
    return {value, value, value};
}

float RoughDielectricBsdf::pdf(const Vec3f &wi, const Vec3f &wo) const {
    const HalfVector h = halfVector(wi, wo, m_eta);
    if (!h.valid) return 0.f;
    const Vec3f &m = h.m;
    const float wiM = dot(wi, m), woM = dot(wo, m);
    // Where the micro- and macro-surface disagree on a side, smithG1 makes eval and sample 0: so here.
    if (!(wiM * wi.z > 0.f && woM * wo.z > 0.f)) return 0.f;
    const float normalPdf = samplingDistribution(wi.z).pdf(wi.z > 0.f ? wi : -wi, m);
    const float f = fresnelDielectric(wiM, m_eta).reflectance;
    return normalPdf * (h.reflect ? f : 1.f - f) * halfVectorJacobian(wi, wo, m, h.reflect, h.eta);
}

BsdfSample RoughDielectricBsdf::sample(const Vec3f &wi, const Vec2f &u, float uLobe) const {
    BsdfSample s;
    s.wo = Vec3f(0.f, 0.f, 1.f);
    if (wi.z == 0.f) return s;
    // The normal is drawn as seen from wi's side (wi turned above the surface).
    const MicrofacetSample ms = samplingDistribution(wi.z).sample(wi.z > 0.f ? wi : -wi, u.x, u.y);
    if (!(ms.pdf > 0.f)) return s;
    const Vec3f m = ms.m;
    const float wiM = dot(wi, m);
    const Fresnel fresnel = fresnelDielectric(wiM, m_eta);
    const Vec3f wo = uLobe <= fresnel.reflectance
                         ? m * (2.f * wiM) - wi
                         : m * (wiM * fresnel.etaTi + fresnel.cosThetaT) - wi * fresnel.etaTi;
    // Where wi or wo sees the microfacet's back, Smith's masking is 0: nothing is drawn (as Mitsuba).
    if (!(wiM * wi.z > 0.f && dot(wo, m) * wo.z > 0.f)) return s;
    // The weight and pdf at wi and wo's half vector, as eval and pdf compute it: the drawn normal differs from it
    // by rounding, which near the critical angle moves F by more than a part in a thousand. Drawn from visible
    // normals, value / pdf is Mitsuba's weight, G1(wo, m) (times eta_ti^2 across); else it is Mitsuba's times
    // D / D_widened, the normal being drawn from the widened roughness (Mitsuba takes it as drawn from D).
    const float pdf = this->pdf(wi, wo), value = eval(wi, wo).x;
    const float weight = value / pdf;
    if (!(pdf > 0.f && value > 0.f && std::isfinite(weight) && std::isfinite(pdf))) return s;
    s.wo = wo;
    s.weight = Color(weight, weight, weight);
    s.pdf = pdf;
    if (wo.z * wi.z < 0.f) s.eta = 1.f / fresnel.etaTi;
    return s;
}

BsdfSample RoughDielectricBsdf::sample(const Vec3f &wi, const Vec2f &u) const {
    return sample(wi, u, hashedUniform(u));
}

}  // namespace mcval
