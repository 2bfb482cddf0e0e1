// Sample warps: maps from uniform samples on [0,1)^2 to other distributions,
// each beside its density. Names follow Nori (squareToX / squareToXPdf) and map
// one-to-one onto Mitsuba's mi.warp.square_to_x / square_to_x_pdf.
//
// Every sampler returns a point strictly inside the support of its density, so
// that pdf(sample) is finite and positive even for u = 0 or u = 1. Inputs at the
// ends of [0,1] are pulled in by at most 2^-24, a change of measure 6e-8.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "float_bits.h"
#include "log_exp.h"
#include "sincos.h"
#include "vector.h"

namespace mcval {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv2Pi = 0.15915494309189533577f;
constexpr float kInv4Pi = 0.07957747154594766788f;

/// Largest float below 1 and its mirror image near 0: the ends of an open [0,1).
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;
constexpr float kSampleFloor = 0x1p-24f;

/// Slack on "inside the unit disk" for points rounded to float.
constexpr float kUnitTolerance = 1e-5f;

namespace detail {
/// u clamped to [2^-24, 1 - 2^-24]: keeps warps off the support's boundary.
inline float openUnit(float u) { return std::min(std::max(u, kSampleFloor), kOneMinusEpsilon); }

/// sqrt that returns 0 for inputs made slightly negative by rounding.
inline float safeSqrt(float x) { return std::sqrt(std::max(x, 0.f)); }

/// pick ? a : b, as a blend of the bits: GCC turns a ?: of two floats into branches that it then
/// duplicates the work after into (two square roots in SIMD where one is needed).
inline float blend(bool pick, float a, float b) {
    const uint32_t mask = 0u - static_cast<uint32_t>(pick);
    return bitsToFloat((floatToBits(a) & mask) | (floatToBits(b) & ~mask));
}

/// Inverse CDF of the 1D tent density 1 - |x| on [-1, 1]: sqrt(2u) - 1 below 1/2, 1 - sqrt(2 - 2u)
/// above, with one root for both halves (2 - 2u = 2 (1 - u) in float: the product by 2 is exact) and
/// the sign of u - 1/2 (sqrt(2u) < 1 below 1/2, so no zero changes sign). The same bits as the two-root
/// form for every float u (checked exhaustively), 1.4x faster in SIMD.
inline float tentInverse(float u) {
    u = openUnit(u);
    const float root = std::sqrt(2.f * blend(u < 0.5f, u, 1.f - u));
    return std::copysign(1.f - root, u - 0.5f);
}

/// Unit direction from cos(theta) and the azimuth phi = 2 pi v.
inline Vec3f sphericalDirection(float cosTheta, float sinTheta, float v) {
    float sinPhi, cosPhi;
    sinCos2Pi(v, sinPhi, cosPhi);
    return {sinTheta * cosPhi, sinTheta * sinPhi, cosTheta};
}
}  // namespace detail

/// Identity on [0,1)^2.
inline Vec2f squareToUniformSquare(const Vec2f &u) { return u; }
/// Density w.r.t. area on [0,1]^2: 1 inside, 0 outside.
inline float squareToUniformSquarePdf(const Vec2f &p) {
    return (p.x >= 0.f && p.x <= 1.f && p.y >= 0.f && p.y <= 1.f) ? 1.f : 0.f;
}

/// Separable tent on [-1,1]^2, by inverting each 1D CDF.
inline Vec2f squareToTent(const Vec2f &u) {
    return {detail::tentInverse(u.x), detail::tentInverse(u.y)};
}
/// Density w.r.t. area: (1 - |x|)(1 - |y|) on [-1,1]^2, 0 outside.
inline float squareToTentPdf(const Vec2f &p) {
    if (std::abs(p.x) > 1.f || std::abs(p.y) > 1.f) return 0.f;
    return (1.f - std::abs(p.x)) * (1.f - std::abs(p.y));
}

/// Uniform on the unit disk: radius sqrt(u.x), angle 2 pi u.y.
inline Vec2f squareToUniformDisk(const Vec2f &u) {
    const float r = std::sqrt(std::max(u.x, 0.f));
    float sinPhi, cosPhi;
    detail::sinCos2Pi(u.y, sinPhi, cosPhi);
    return {r * cosPhi, r * sinPhi};
}
/// Density w.r.t. area: 1/pi on the unit disk, 0 outside.
inline float squareToUniformDiskPdf(const Vec2f &p) {
    return (p.x * p.x + p.y * p.y <= 1.f + kUnitTolerance) ? kInvPi : 0.f;
}

/// Uniform on the unit sphere: z = 1 - 2 u.x, azimuth 2 pi u.y.
inline Vec3f squareToUniformSphere(const Vec2f &u) {
    const float z = std::fma(-2.f, u.x, 1.f);  // 2 u.x is exact: the bits of 1 - 2 u.x, in one operation
    // 1 - z^2 = 4 u (1 - u), exact near the poles where 1 - z*z cancels.
    const float sinTheta = 2.f * detail::safeSqrt(u.x * (1.f - u.x));
    return detail::sphericalDirection(z, sinTheta, u.y);
}
/// Density w.r.t. solid angle: 1/(4 pi) everywhere on the sphere.
inline float squareToUniformSpherePdf(const Vec3f &) { return kInv4Pi; }

/// Uniform on the hemisphere z > 0: z = 1 - u.x, azimuth 2 pi u.y.
inline Vec3f squareToUniformHemisphere(const Vec2f &u) {
    const float ux = detail::openUnit(u.x);
    const float z = 1.f - ux;
    const float sinTheta = detail::safeSqrt(ux * (2.f - ux));  // 1 - z^2 without cancellation
    return detail::sphericalDirection(z, sinTheta, u.y);
}
/// Density w.r.t. solid angle: 1/(2 pi) for z >= 0, 0 below the horizon.
inline float squareToUniformHemispherePdf(const Vec3f &v) { return v.z >= 0.f ? kInv2Pi : 0.f; }

/// Cosine-weighted hemisphere: a uniform disk sample lifted onto the hemisphere.
inline Vec3f squareToCosineHemisphere(const Vec2f &u) {
    const float ux = detail::openUnit(u.x);
    // r^2 = u.x, so z = sqrt(1 - r^2) = sqrt(1 - u.x), and 1 - u.x is exact for u.x >= 1/2.
    return detail::sphericalDirection(std::sqrt(1.f - ux), std::sqrt(ux), u.y);
}
/// Density w.r.t. solid angle: cos(theta)/pi for z > 0, 0 otherwise.
inline float squareToCosineHemispherePdf(const Vec3f &v) { return v.z > 0.f ? v.z * kInvPi : 0.f; }

/// Beckmann microfacet normals, distributed as D(m) cos(theta_m):
/// tan^2(theta) = -alpha^2 log(1 - u.y), azimuth 2 pi u.x.
inline Vec3f squareToBeckmann(const Vec2f &u, float alpha) {
    const float tan2Theta = -alpha * alpha * detail::log1pNonPositive(-detail::openUnit(u.y));
    const float cosTheta = 1.f / std::sqrt(1.f + tan2Theta);
    const float sinTheta = std::sqrt(tan2Theta) * cosTheta;
    return detail::sphericalDirection(cosTheta, sinTheta, u.x);
}
/// Density w.r.t. solid angle: D(m) cos(theta) = exp(-tan^2/alpha^2) / (pi alpha^2 cos^3),
/// 0 for z <= 0.
inline float squareToBeckmannPdf(const Vec3f &m, float alpha) {
    const float cos3 = m.z * m.z * m.z;
    const float exponent = (m.x * m.x + m.y * m.y) / (m.z * m.z * alpha * alpha);
    // Far in the tail exp() underflows while cos^3 may reach 0: the density is 0 there. Operands
    // selected, not results, so that arrays of it run in SIMD (no division in one arm of a ?:).
    const bool zero = !(m.z > 0.f) || !(exponent <= 87.f) || cos3 == 0.f;
    const float density = detail::expNegative(zero ? 0.f : exponent) / (kPi * alpha * alpha * (zero ? 1.f : cos3));
    return zero ? 0.f : density;
}

}  // namespace mcval
