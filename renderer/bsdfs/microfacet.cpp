// Mitsuba 3's MicrofacetDistribution, isotropic (include/mitsuba/render/microfacet.h).
#include "microfacet.h"

#include <algorithm>
#include <cmath>

#include "../warp.h"

namespace mcval {

namespace {

constexpr float kInvSqrtPi = 0.56418958354775628695f;

/// erf^-1 in single precision (Giles 2010, "Approximating the erfinv function"), as Dr.Jit computes it.
float erfinv(float x) {
    float w = -std::log((1.f - x) * (1.f + x)), p;
    if (w < 5.f) {
        w -= 2.5f;
        p = 2.81022636e-08f;
        p = 3.43273939e-07f + p * w;
        p = -3.5233877e-06f + p * w;
        p = -4.39150654e-06f + p * w;
        p = 0.00021858087f + p * w;
        p = -0.00125372503f + p * w;
        p = -0.00417768164f + p * w;
        p = 0.246640727f + p * w;
        p = 1.50140941f + p * w;
    } else {
        w = std::sqrt(w) - 3.f;
        p = -0.000200214257f;
        p = 0.000100950558f + p * w;
        p = 0.00134934322f + p * w;
        p = -0.00367342844f + p * w;
        p = 0.00573950773f + p * w;
        p = -0.0076224613f + p * w;
        p = 0.00943887047f + p * w;
        p = 1.00167406f + p * w;
        p = 2.83297682f + p * w;
    }
    return p * x;
}

float sqr(float x) { return x * x; }

}  // namespace

float MicrofacetDistribution::eval(const Vec3f &m) const {
    const float a2 = m_alpha * m_alpha, cos2 = m.z * m.z;
    const float result = m_type == Type::Beckmann
                             ? std::exp(-(m.x * m.x + m.y * m.y) / (a2 * cos2)) / (kPi * a2 * cos2 * cos2)
                             : 1.f / (kPi * a2 * sqr((m.x * m.x + m.y * m.y) / a2 + cos2));
    // As Mitsuba: no density where it would underflow the stages after it (and none below the surface).
    return result * m.z > 1e-20f ? result : 0.f;
}

float MicrofacetDistribution::smithG1(const Vec3f &v, const Vec3f &m) const {
    if (dot(v, m) * v.z <= 0.f) return 0.f;  // the back of the microfacet
    const float xyAlpha2 = m_alpha * m_alpha * (v.x * v.x + v.y * v.y);
    if (xyAlpha2 == 0.f) return 1.f;  // perpendicular incidence: no masking
    const float tanThetaAlpha2 = xyAlpha2 / (v.z * v.z);
    if (m_type == Type::Beckmann) {
        // Smith's exact 1 / (1 + Lambda(a)): the visible normals' density then integrates to 1 and is the one
        // sample() draws. Mitsuba's rational approximation (Walter et al. 2007) does neither at grazing angles
        // (docs/findings.md).
        const float a = 1.f / std::sqrt(tanThetaAlpha2);
        const float lambda = 0.5f * (std::erf(a) - 1.f) + std::exp(-a * a) / (2.f * a * std::sqrt(kPi));
        return 1.f / (1.f + lambda);
    }
    return 2.f / (1.f + std::sqrt(1.f + tanThetaAlpha2));
}

float MicrofacetDistribution::pdf(const Vec3f &wi, const Vec3f &m) const {
    const float d = eval(m);
    return m_sampleVisible ? d * smithG1(wi, m) * std::abs(dot(wi, m)) / wi.z : d * m.z;
}

void MicrofacetDistribution::sampleVisible11(float cosThetaI, float u1, float u2, float &slopeX,
                                             float &slopeY) const {
    if (m_type == Type::GGX) {
        const Vec2f disk = squareToUniformDisk(Vec2f(u1, u2));
        const float s = 0.5f * (1.f + cosThetaI);
        const float x = disk.x, y = (1.f - s) * detail::safeSqrt(1.f - x * x) + s * disk.y;
        const float z = detail::safeSqrt(1.f - x * x - y * y);
        const float sinThetaI = detail::safeSqrt(1.f - cosThetaI * cosThetaI);
        const float norm = 1.f / (sinThetaI * y + cosThetaI * z);
        slopeX = (cosThetaI * y - sinThetaI * z) * norm;
        slopeY = x * norm;
        return;
    }
    // Beckmann: Mitsuba's numerical inversion of the slope CDF, parameterised in erf's domain.
    const float tanThetaI = detail::safeSqrt(1.f - cosThetaI * cosThetaI) / cosThetaI;
    const float cotThetaI = 1.f / tanThetaI;
    const float maxval = std::erf(cotThetaI);
    u1 = std::max(u1, 1e-6f);
    const float thetaI = std::acos(cosThetaI);
    const float fit = 1.f + thetaI * (-0.876f + thetaI * (0.4265f - 0.0594f * thetaI));
    float b = maxval - (1.f + maxval) * std::pow(1.f - u1, fit);
    const float normalization = 1.f / (1.f + maxval + kInvSqrtPi * tanThetaI * std::exp(-cotThetaI * cotThetaI));
    for (int i = 0; i < 3; ++i) {  // three Newton steps
        const float x = erfinv(b);
        const float value = normalization * (1.f + b + kInvSqrtPi * tanThetaI * std::exp(-x * x)) - u1;
        const float derivative = normalization * (1.f - x * tanThetaI);
        b -= value / derivative;
    }
    slopeX = erfinv(b);
    slopeY = erfinv(2.f * std::max(u2, 1e-6f) - 1.f);
}

MicrofacetSample MicrofacetDistribution::sample(const Vec3f &wi, float u1, float u2) const {
    MicrofacetSample s;
    if (!m_sampleVisible) {
        const float a2 = m_alpha * m_alpha;
        const float tan2 = m_type == Type::Beckmann ? -a2 * std::log(1.f - u1) : a2 * u1 / (1.f - u1);
        const float cosM = 1.f / std::sqrt(1.f + tan2), cos3 = cosM * cosM * cosM;
        s.pdf = m_type == Type::Beckmann ? (1.f - u1) / (kPi * a2 * cos3)
                                         : 1.f / (kPi * a2 * cos3 * sqr(1.f + tan2 / a2));
        const float sinM = std::sqrt(tan2) * cosM;  // not sqrt(1 - cos^2): that cancels for small tan2
        const float phi = 2.f * kPi * u2;
        s.m = Vec3f(std::cos(phi) * sinM, std::sin(phi) * sinM, cosM);
        return s;
    }
    // Stretch wi to unit roughness, sample a slope seen from there, rotate and unstretch it.
    const Vec3f wiP = normalize(Vec3f(m_alpha * wi.x, m_alpha * wi.y, wi.z));
    const float sinTheta2 = 1.f - wiP.z * wiP.z;
    float sinPhi = 0.f, cosPhi = 1.f;
    if (sinTheta2 > 4.f * 0x1p-24f) {
        const float inv = 1.f / std::sqrt(sinTheta2);
        sinPhi = std::clamp(wiP.y * inv, -1.f, 1.f), cosPhi = std::clamp(wiP.x * inv, -1.f, 1.f);
    }
    float sx, sy;
    sampleVisible11(wiP.z, u1, u2, sx, sy);
    const float slopeX = (cosPhi * sx - sinPhi * sy) * m_alpha, slopeY = (sinPhi * sx + cosPhi * sy) * m_alpha;
    s.m = normalize(Vec3f(-slopeX, -slopeY, 1.f));
    s.pdf = eval(s.m) * smithG1(wi, s.m) * std::abs(dot(wi, s.m)) / wi.z;
    return s;
}

}  // namespace mcval
