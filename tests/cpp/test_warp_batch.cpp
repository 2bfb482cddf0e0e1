// The array warps (warp_batch.h) against the scalar ones of warp.h, bit for bit, on random inputs and
// on the hard ones (the ends of [0, 1), a half, the smallest floats), in rows of every remainder length.
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "warp.h"
#include "warp_batch.h"

using namespace mcval;

namespace {

/// Uniform rows: the hard values first (every pair of them), then random ones; `rows` in all.
std::vector<float> uniformRows(size_t rows, unsigned seed) {
    const float hard[] = {0.f, 0x1p-24f, 1e-30f, 0x1p-126f, 0.25f, 0.5f, 0x1.fffffep-2f, 0x1.000002p-1f, 0.75f,
                          0x1.fffffep-1f, 1.f};
    std::vector<float> u;
    for (float a : hard)
        for (float b : hard) u.insert(u.end(), {a, b});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(0.f, 1.f);
    while (u.size() < 2 * rows) u.push_back(dist(rng));
    u.resize(2 * rows);
    return u;
}

/// Points in (and a little beyond) [-1.1, 1.1]^Dim, with 0 and +-1 among them.
std::vector<float> pointRows(size_t rows, int dim, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> dist(-1.1f, 1.1f);
    std::vector<float> p(rows * dim);
    for (size_t i = 0; i < p.size(); ++i) p[i] = i % 7 == 0 ? float(int(i % 3) - 1) : dist(rng);
    return p;
}

void store(float *row, const Vec2f &v) { row[0] = v.x; row[1] = v.y; }
void store(float *row, const Vec3f &v) { row[0] = v.x; row[1] = v.y; row[2] = v.z; }
void store(float *row, float v) { row[0] = v; }
Vec2f load2(const float *row) { return {row[0], row[1]}; }
Vec3f load3(const float *row) { return {row[0], row[1], row[2]}; }

/// The batch over `in` and the scalar function row by row agree bit for bit, for n rows and fewer.
template <int InDim, typename Batch, typename Scalar>
void expectSameBits(Batch batch, Scalar scalar, const std::vector<float> &in, int outDim) {
    const size_t rows = in.size() / InDim;
    for (size_t n : {rows, rows - 1, size_t(15), size_t(17), size_t(1), size_t(0)}) {
        std::vector<float> got(n * outDim + 1, -7.f), want(n * outDim + 1, -7.f);
        batch(in.data(), got.data(), n);
        for (size_t r = 0; r < n; ++r) {
            if constexpr (InDim == 2) store(&want[r * outDim], scalar(load2(&in[r * InDim])));
            else store(&want[r * outDim], scalar(load3(&in[r * InDim])));
        }
        ASSERT_EQ(0, std::memcmp(got.data(), want.data(), got.size() * sizeof(float))) << n << " rows";
    }
}

}  // namespace

TEST(WarpBatch, SamplersMatchTheScalarWarpsBitForBit) {
    const std::vector<float> u = uniformRows(4099, 1);
    expectSameBits<2>(squareToUniformSquareBatch, [](const Vec2f &v) { return squareToUniformSquare(v); }, u, 2);
    expectSameBits<2>(squareToTentBatch, [](const Vec2f &v) { return squareToTent(v); }, u, 2);
    expectSameBits<2>(squareToUniformDiskBatch, [](const Vec2f &v) { return squareToUniformDisk(v); }, u, 2);
    expectSameBits<2>(squareToUniformSphereBatch, [](const Vec2f &v) { return squareToUniformSphere(v); }, u, 3);
    expectSameBits<2>(squareToUniformHemisphereBatch, [](const Vec2f &v) { return squareToUniformHemisphere(v); }, u, 3);
    expectSameBits<2>(squareToCosineHemisphereBatch, [](const Vec2f &v) { return squareToCosineHemisphere(v); }, u, 3);
    for (float alpha : {0.05f, 0.3f, 1.f})
        expectSameBits<2>([alpha](const float *in, float *out, size_t n) { squareToBeckmannBatch(in, out, n, alpha); },
                          [alpha](const Vec2f &v) { return squareToBeckmann(v, alpha); }, u, 3);
}

TEST(WarpBatch, PdfsMatchTheScalarPdfsBitForBit) {
    const std::vector<float> p2 = pointRows(4099, 2, 2), p3 = pointRows(4099, 3, 3);
    expectSameBits<2>(squareToUniformSquarePdfBatch, [](const Vec2f &v) { return squareToUniformSquarePdf(v); }, p2, 1);
    expectSameBits<2>(squareToTentPdfBatch, [](const Vec2f &v) { return squareToTentPdf(v); }, p2, 1);
    expectSameBits<2>(squareToUniformDiskPdfBatch, [](const Vec2f &v) { return squareToUniformDiskPdf(v); }, p2, 1);
    expectSameBits<3>(squareToUniformSpherePdfBatch, [](const Vec3f &v) { return squareToUniformSpherePdf(v); }, p3, 1);
    expectSameBits<3>(squareToUniformHemispherePdfBatch, [](const Vec3f &v) { return squareToUniformHemispherePdf(v); }, p3, 1);
    expectSameBits<3>(squareToCosineHemispherePdfBatch, [](const Vec3f &v) { return squareToCosineHemispherePdf(v); }, p3, 1);
    for (float alpha : {0.05f, 0.3f, 1.f})
        expectSameBits<3>([alpha](const float *in, float *out, size_t n) { squareToBeckmannPdfBatch(in, out, n, alpha); },
                          [alpha](const Vec3f &v) { return squareToBeckmannPdf(v, alpha); }, p3, 1);
}

TEST(WarpBatch, TheBitTestCatchesAWarpThatDiffersInOneUlp) {
    // The comparison itself can fail: a tent whose x is one ulp off in one row.
    const std::vector<float> u = uniformRows(64, 4);
    std::vector<float> got(128), want(128);
    squareToTentBatch(u.data(), got.data(), 64);
    for (size_t r = 0; r < 64; ++r) store(&want[2 * r], squareToTent(load2(&u[2 * r])));
    EXPECT_EQ(0, std::memcmp(got.data(), want.data(), got.size() * sizeof(float)));
    want[10] = std::nextafter(want[10], 2.f);
    EXPECT_NE(0, std::memcmp(got.data(), want.data(), got.size() * sizeof(float)));
}
