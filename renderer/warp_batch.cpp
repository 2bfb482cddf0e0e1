#include "warp_batch.h"

#include "hot.h"
#include "warp.h"

namespace mcval {

namespace {


template <int Dim>
struct Row;
template <>
struct Row<1> { using Type = float; };
template <>
struct Row<2> { using Type = Vec2f; };
template <>
struct Row<3> { using Type = Vec3f; };

template <int Dim>
__attribute__((always_inline)) inline typename Row<Dim>::Type loadLane(const float (&a)[Dim][1], int i) {
    if constexpr (Dim == 2) return Vec2f(a[0][i], a[1][i]);
    else return Vec3f(a[0][i], a[1][i], a[2][i]);
}

__attribute__((always_inline)) inline void storeLane(float (&r)[1][1], int i, float v) { r[0][i] = v; }
__attribute__((always_inline)) inline void storeLane(float (&r)[2][1], int i, const Vec2f &v) {
    r[0][i] = v.x;
    r[1][i] = v.y;
}
__attribute__((always_inline)) inline void storeLane(float (&r)[3][1], int i, const Vec3f &v) {
    r[0][i] = v.x;
    r[1][i] = v.y;
    r[2][i] = v.z;
}

/// f over rows one at a time, the rows' coordinates loaded and stored in place (for the last rows).
template <int InDim, int OutDim, typename F>
__attribute__((always_inline)) inline void mapEachRow(const float *in, float *out, size_t n, F f) {
    for (size_t row = 0; row < n; ++row) {
        alignas(16) float a[InDim][1];
        alignas(16) float r[OutDim][1];
        for (int d = 0; d < InDim; ++d) a[d][0] = in[row * InDim + d];
        storeLane(r, 0, f(loadLane<InDim>(a, 0)));
        for (int d = 0; d < OutDim; ++d) out[row * OutDim + d] = r[d][0];
    }
}

/// Rows a block: its results, one array per coordinate, stay in the L1 cache.
constexpr size_t kBlock = 64;

/// f over n rows, a block at a time: a loop that reads the rows (GCC's strided loads take them apart)
/// and writes each result coordinate to an array of its own, then one that interleaves the arrays into
/// rows. Both run in SIMD (f is inlined, branch-free); interleaving the results within the first loop
/// costs twice as much in permutations. Inlined into each caller, so that it is compiled for the
/// caller's ISA clone.
template <int InDim, int OutDim, typename F>
__attribute__((always_inline)) inline void mapRows(const float *in, float *out, size_t n, F f) {
    size_t row = 0;
    for (; row + kBlock <= n; row += kBlock) {
        alignas(64) float r[OutDim][kBlock];
        const float *src = in + row * InDim;
        for (size_t i = 0; i < kBlock; ++i) {
            alignas(16) float a[InDim][1];
            alignas(16) float v[OutDim][1];
            for (int d = 0; d < InDim; ++d) a[d][0] = src[i * InDim + d];
            storeLane(v, 0, f(loadLane<InDim>(a, 0)));
            for (int d = 0; d < OutDim; ++d) r[d][i] = v[d][0];
        }
        float *dst = out + row * OutDim;
        for (size_t i = 0; i < kBlock; ++i)
            for (int d = 0; d < OutDim; ++d) dst[i * OutDim + d] = r[d][i];
    }
    mapEachRow<InDim, OutDim>(in + row * InDim, out + row * OutDim, n - row, f);
}

}  // namespace

#define MCVAL_WARP_BATCH(name, in, outDim)                                                   \
    MCVAL_HOT void name##Batch(const float *src, float *dst, size_t n) {                     \
        mapRows<in, outDim>(src, dst, n, [](const auto &x) { return name(x); });             \
    }

MCVAL_WARP_BATCH(squareToUniformSquare, 2, 2)
MCVAL_WARP_BATCH(squareToUniformSquarePdf, 2, 1)
// The tent is separable and its rows are pairs in, pairs out: one flat map over 2n coordinates, with no
// rows to take apart or put back together.
MCVAL_HOT void squareToTentBatch(const float *src, float *dst, size_t n) {
    for (size_t i = 0; i < 2 * n; ++i) dst[i] = detail::tentInverse(src[i]);
}
MCVAL_WARP_BATCH(squareToTentPdf, 2, 1)
MCVAL_WARP_BATCH(squareToUniformDisk, 2, 2)
MCVAL_WARP_BATCH(squareToUniformDiskPdf, 2, 1)
MCVAL_WARP_BATCH(squareToUniformSphere, 2, 3)
MCVAL_WARP_BATCH(squareToUniformSpherePdf, 3, 1)
MCVAL_WARP_BATCH(squareToUniformHemisphere, 2, 3)
MCVAL_WARP_BATCH(squareToUniformHemispherePdf, 3, 1)
MCVAL_WARP_BATCH(squareToCosineHemisphere, 2, 3)
MCVAL_WARP_BATCH(squareToCosineHemispherePdf, 3, 1)

MCVAL_HOT void squareToBeckmannBatch(const float *src, float *dst, size_t n, float alpha) {
    mapRows<2, 3>(src, dst, n, [alpha](const Vec2f &u) { return squareToBeckmann(u, alpha); });
}
MCVAL_HOT void squareToBeckmannPdfBatch(const float *src, float *dst, size_t n, float alpha) {
    mapRows<3, 1>(src, dst, n, [alpha](const Vec3f &m) { return squareToBeckmannPdf(m, alpha); });
}

}  // namespace mcval
