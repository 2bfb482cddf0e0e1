// log1p and exp in float without branches or library calls, so that a loop over many values runs in SIMD
// (glibc's log1pf and expf are scalar calls); the same operations, hence the same bits, in every ISA
// clone. Cephes' minimax polynomials (logf, expf) after a reduction by the exponent; within 2 float ulps
// of the exact values on the ranges the film and the warps use.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "float_bits.h"

namespace mcval {

/// e^x for x <= 0, to 2 ulp (Cephes' expf: x = n ln2 + r, a degree-7 polynomial in r, times 2^n), in
/// plain multiplies and adds, so that a loop of them vectorises and every target_clone gives the
/// same bits. Below -87 (where 2^n would leave the normal floats) it returns e^-87 (~1.6e-38).
inline float expNonPositive(float x) {
    x = std::max(x, -87.f);
    const float n = (x * 1.44269504f + 12582912.f) - 12582912.f;  // x / ln2 rounded to an integer
    float r = x - n * 0.693359375f;  // exact: ln2's high part has 9 bits, n at most 8
    r = r - n * -2.12194440e-4f;
    float p = 1.9875691500e-4f;
    p = p * r + 1.3981999507e-3f;
    p = p * r + 8.3334519073e-3f;
    p = p * r + 4.1665795894e-2f;
    p = p * r + 1.6666665459e-1f;
    p = p * r + 5.0000001201e-1f;
    p = p * (r * r) + r + 1.f;
    const int32_t bits = (static_cast<int32_t>(n) + 127) << 23;
    return p * detail::bitsToFloat(static_cast<uint32_t>(bits));
}

}  // namespace mcval

namespace mcval::detail {

/// log(x) for finite x > 0 (normal floats).
inline float logPositive(float x) {
    // x = m 2^e with m in [sqrt(1/2), sqrt(2)): m - 1 is small, where the polynomial is accurate.
    const uint32_t bits = floatToBits(x);
    int e = static_cast<int>(bits >> 23) - 126;
    float m = bitsToFloat((bits & 0x007FFFFFu) | 0x3F000000u);  // in [1/2, 1)
    const bool low = m < 0.707106781186547524f;
    e -= low ? 1 : 0;
    m = (low ? m + m : m) - 1.f;
    const float z = m * m;
    // Fused multiply-adds (see sincos.h): the same bits in every clone, half the operations with FMA.
    float y = 7.0376836292e-2f;
    y = std::fma(y, m, -1.1514610310e-1f);
    y = std::fma(y, m, 1.1676998740e-1f);
    y = std::fma(y, m, -1.2420140846e-1f);
    y = std::fma(y, m, 1.4249322787e-1f);
    y = std::fma(y, m, -1.6668057665e-1f);
    y = std::fma(y, m, 2.0000714765e-1f);
    y = std::fma(y, m, -2.4999993993e-1f);
    y = std::fma(y, m, 3.3333331174e-1f);
    y = y * m * z;
    const float fe = static_cast<float>(e);
    y = std::fma(-2.12194440e-4f, fe, y);
    y = std::fma(-0.5f, z, y);
    return (m + y) + 0.693359375f * fe;
}

/// log(1 + x) for x in (-1, 0]: log(u) x / (u - 1) with u = 1 + x rounded, which cancels the rounding of
/// u (Goldberg's rule), and x itself where u rounds to 1.
inline float log1pNonPositive(float x) {
    const float u = 1.f + x;
    const bool one = u == 1.f;
    const float d = one ? 1.f : u - 1.f;
    const float l = logPositive(one ? 1.f : u);
    return one ? x : l * (x / d);
}

/// exp(-y) for y in [0, 87], 0 for larger y (below float's normal range) and for NaN.
inline float expNegative(float y) {
    const bool inRange = y <= 87.f;  // false for NaN
    return inRange ? expNonPositive(inRange ? -y : 0.f) : 0.f;
}

}  // namespace mcval::detail
