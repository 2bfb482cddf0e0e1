// sin and cos of 2 pi v in float, without branches or library calls, so that a packet's lanes compute
// them in SIMD (glibc's sincosf is a scalar call); the same operations, hence the same bits, in every
// ISA clone. Cephes' minimax polynomials on [-pi/4, pi/4] after a reduction in quarter turns; within a
// few float ulps of the exact values. The polynomials are written with fused multiply-adds: one rounding
// each, so every clone gets the same bits (a call to fmaf where the CPU has no FMA), and half the
// operations where it has (the warps are bound by their arithmetic).
#pragma once

#include <cmath>
#include <cstdint>

#include "float_bits.h"

namespace mcval::detail {

inline void sinCos2Pi(float v, float &s, float &c) {
    // v = k/4 + r with |r| <= 1/8: the angle 2 pi r lies in [-pi/4, pi/4].
    const float k = std::nearbyint(4.f * v);
    const float r = std::fma(-0.25f, k, v);  // k / 4 is exact: the bits of v - 0.25 k, in one operation
    const float a = r * 6.28318530717958647692f;
    const float a2 = a * a;
    const float ps = std::fma(a2, std::fma(a2, -1.9515295891e-4f, 8.3321608736e-3f), -1.6666654611e-1f);
    const float sa = std::fma(a * a2, ps, a);
    const float pc = std::fma(a2, std::fma(a2, 2.443315711809948e-5f, -1.388731625493765e-3f), 4.166664568298827e-2f);
    const float ca = std::fma(a2 * a2, pc, std::fma(-0.5f, a2, 1.f));
    // Rotate by k quarter turns: (sin, cos) -> (cos, -sin) per quarter. The signs flip as bit 1 of k
    // (for sin) and of k + 1 (for cos) says: that bit moved to the sign bit, an exclusive or.
    const uint32_t q = static_cast<uint32_t>(static_cast<int32_t>(k));
    const bool odd = (q & 1u) != 0;
    const float sq = odd ? ca : sa, cq = odd ? sa : ca;
    s = bitsToFloat(floatToBits(sq) ^ ((q & 2u) << 30));
    c = bitsToFloat(floatToBits(cq) ^ (((q + 1u) & 2u) << 30));
}

}  // namespace mcval::detail
