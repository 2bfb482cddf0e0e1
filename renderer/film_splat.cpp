// A wide (gaussian or tent) filter's splat of a pixel's packet of samples: ImageBlock::putWide.
#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "film.h"
#include "hot.h"

namespace mcval {

namespace {

constexpr int P = ImageBlock::kMaxPacket;

// GCC/Clang vectors: elementwise, so each target_clone computes the same bits (in 512-, 256- or
// 128-bit registers).
typedef double V4 __attribute__((vector_size(32)));
typedef double V8 __attribute__((vector_size(64)));
// The same at any address (a pixel's sums: 11 doubles).
typedef double V4u __attribute__((vector_size(32), aligned(8)));
typedef double V8u __attribute__((vector_size(64), aligned(8)));

/// Bit k set where w[k] > 0, for the 16 (64-byte aligned) w[k].
inline uint32_t positiveLanes(const float *w) {
    uint32_t mask = 0;
#if defined(__SSE2__)
    for (int q = 0; q < P / 4; ++q)
        mask |= static_cast<uint32_t>(_mm_movemask_ps(_mm_cmpgt_ps(_mm_load_ps(w + 4 * q), _mm_setzero_ps()))) << (4 * q);
#else
    for (int k = 0; k < P; ++k) mask |= static_cast<uint32_t>(w[k] > 0.f) << k;
#endif
    return mask;
}

/// The 1D filter weights of a packet's lanes on the window's taps: w[o * 16 + k] for the pixel at
/// first + o and lane k (the weight put() gives), and per tap the bit mask of the lanes (< count)
/// with a non-zero weight there. `weight(d)`: the filter at offset d.
template <typename Weight>
MCVAL_HOT void tapWeights(int first, int taps, const float *pos, int count, const Weight &weight, float *w,
                          uint32_t *masks) {
    alignas(64) float p[P];
    for (int k = 0; k < P; ++k) p[k] = pos[std::min(k, count - 1)];
    for (int o = 0; o < taps; ++o) {
        const float centre = static_cast<float>(first + o) + 0.5f;
        float *wo = &w[o * P];
        for (int k = 0; k < P; ++k) {
            wo[k] = weight(centre - p[k]);
        }
        masks[o] = positiveLanes(wo) & ((1u << count) - 1u);
    }
}

/// Adds to the sums of N adjacent pixels of one row (at dst) the lanes in `lanes`, in lane order,
/// summed in registers first: lane k's x weights a[i * 16 + k] (and their squares a2) times its y
/// weight b[k] times (1, L) and b2[k] = b^2 times (1, L, L^2, 0).
template <int N>
inline __attribute__((always_inline)) void splatColumns(uint32_t lanes, const double *a, const double *a2,
                                                        const double *b, const double *b2, const V4 *lw,
                                                        const V8 *lw2, double *dst) {
    V4 accW[N] = {};
    V8 accW2[N] = {};
    do {
        const int k = __builtin_ctz(lanes);
        lanes &= lanes - 1;
        const V4 w = b[k] * lw[k];
        const V8 w2 = b2[k] * lw2[k];
        for (int i = 0; i < N; ++i) {
            accW[i] += a[i * P + k] * w;
            accW2[i] += a2[i * P + k] * w2;
        }
    } while (lanes);
    // Whole vectors: the last (0) adds to the pixel's padding.
    for (int i = 0; i < N; ++i) {
        V4u *s = reinterpret_cast<V4u *>(&dst[ImageBlock::kStride * i]);
        V8u *s2 = reinterpret_cast<V8u *>(&dst[ImageBlock::kStride * i + 4]);
        *s += accW[i];
        *s2 += accW2[i];
    }
}

}  // namespace

MCVAL_HOT void ImageBlock::putWide(int x, int y, const float *fx, const float *fy, const Color *L, int count) {
    if (count <= 0) return;
    // 0 x inf would spread a non-finite sample onto pixels of weight 0, which put() skips.
    bool finite = true;
    for (int k = 0; k < count; ++k) finite &= std::isfinite(L[k][0]) & std::isfinite(L[k][1]) & std::isfinite(L[k][2]);
    if (!finite) {
        for (int k = 0; k < count; ++k) put(fx[k], fy[k], L[k]);
        return;
    }
    const int taps = 2 * m_taps + 1, firstX = x - m_taps, firstY = y - m_taps;
    alignas(64) float wx[kMaxTaps * P], wy[kMaxTaps * P];
    uint32_t maskX[kMaxTaps], maskY[kMaxTaps];
    if (m_filter.type == FilterSpec::Type::Tent) {
        const float inv = m_invRadius;
        const auto tent = [inv](float d) { return tentWeight(d, inv); };
        tapWeights(firstX, taps, fx, count, tent, wx, maskX);
        tapWeights(firstY, taps, fy, count, tent, wy, maskY);
    } else {
        const float alpha = m_alpha, edge = m_edge;
        const auto gaussian = [alpha, edge](float d) { return std::max(0.f, expNonPositive(alpha * d * d) - edge); };
        tapWeights(firstX, taps, fx, count, gaussian, wx, maskX);
        tapWeights(firstY, taps, fy, count, gaussian, wy, maskY);
    }

    // The weights in double (a product of two is exact), and each lane's (1, L) and (1, L, L^2, 0):
    // a pixel's 11 sums are a b (1, L) and a^2 b^2 (1, L, L^2) summed over the lanes.
    const uintptr_t base = reinterpret_cast<uintptr_t>(m_scratch.data());  // aligned to 64 bytes
    double *a1 = reinterpret_cast<double *>((base + 63) & ~uintptr_t(63));
    double *a2 = a1 + taps * P, *b1 = a2 + taps * P, *b2 = b1 + taps * P;
    for (int i = 0; i < taps * P; ++i) {
        a1[i] = wx[i];
        a2[i] = a1[i] * a1[i];
        b1[i] = wy[i];
        b2[i] = b1[i] * b1[i];
    }
    alignas(64) V4 lw[P];
    alignas(64) V8 lw2[P];
    for (int k = 0; k < count; ++k) {
        const double l0 = L[k][0], l1 = L[k][1], l2 = L[k][2];
        lw[k] = V4{1.0, l0, l1, l2};
        lw2[k] = V8{1.0, l0, l1, l2, l0 * l0, l1 * l1, l2 * l2, 0.0};
    }

    // Only the window's pixels inside the block (the others have weight 0), a row at a time, in chunks
    // of up to 5 columns whose sums stay in registers (independent chains) over the lanes.
    const int oxLo = std::max(0, m_x0 - firstX), oxHi = std::min(taps, m_x0 + m_width - firstX);
    const int oyLo = std::max(0, m_y0 - firstY), oyHi = std::min(taps, m_y0 + m_height - firstY);
    for (int oy = oyLo; oy < oyHi; ++oy) {
        if (!maskY[oy]) continue;
        const double *b = &b1[oy * P], *bb = &b2[oy * P];
        double *dst = &m_data[kStride * ((firstY + oy - m_y0) * m_width + (firstX - m_x0))];
        for (int ox = oxLo; ox < oxHi; ox += 5) {
            const int n = std::min(5, oxHi - ox);
            uint32_t lanes = 0;
            for (int i = 0; i < n; ++i) lanes |= maskX[ox + i];
            lanes &= maskY[oy];
            if (!lanes) continue;
            const double *a = &a1[ox * P], *aa = &a2[ox * P];
            double *d = &dst[kStride * ox];
            switch (n) {
            case 5: splatColumns<5>(lanes, a, aa, b, bb, lw, lw2, d); break;
            case 4: splatColumns<4>(lanes, a, aa, b, bb, lw, lw2, d); break;
            case 3: splatColumns<3>(lanes, a, aa, b, bb, lw, lw2, d); break;
            case 2: splatColumns<2>(lanes, a, aa, b, bb, lw, lw2, d); break;
            default: splatColumns<1>(lanes, a, aa, b, bb, lw, lw2, d); break;
            }
        }
    }
}

}  // namespace mcval
