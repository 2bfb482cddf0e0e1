// The sample warps of warp.h over whole arrays of rows (N x 2 uniforms in, N x 2 or N x 3 points out;
// points in, N densities out), 16 rows at a time in SIMD: each call computes, row for row, what the
// scalar function returns (the same operations, hence the same bits), and is compiled per ISA
// (hot.h). The Python binding hands each thread a range of rows.
#pragma once

#include <cstddef>

namespace mcval {

/// A warp over rows: reads n rows of `in`, writes n rows of `out`.
using WarpBatch = void (*)(const float *in, float *out, size_t n);
/// A warp with a parameter (Beckmann's alpha).
using WarpBatchWith = void (*)(const float *in, float *out, size_t n, float alpha);

void squareToUniformSquareBatch(const float *in, float *out, size_t n);
void squareToUniformSquarePdfBatch(const float *in, float *out, size_t n);
void squareToTentBatch(const float *in, float *out, size_t n);
void squareToTentPdfBatch(const float *in, float *out, size_t n);
void squareToUniformDiskBatch(const float *in, float *out, size_t n);
void squareToUniformDiskPdfBatch(const float *in, float *out, size_t n);
void squareToUniformSphereBatch(const float *in, float *out, size_t n);
void squareToUniformSpherePdfBatch(const float *in, float *out, size_t n);
void squareToUniformHemisphereBatch(const float *in, float *out, size_t n);
void squareToUniformHemispherePdfBatch(const float *in, float *out, size_t n);
void squareToCosineHemisphereBatch(const float *in, float *out, size_t n);
void squareToCosineHemispherePdfBatch(const float *in, float *out, size_t n);
void squareToBeckmannBatch(const float *in, float *out, size_t n, float alpha);
void squareToBeckmannPdfBatch(const float *in, float *out, size_t n, float alpha);

}  // namespace mcval
