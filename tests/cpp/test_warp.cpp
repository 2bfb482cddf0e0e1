// Warps on hard inputs: every sample finite, in its domain, with a finite positive pdf.
// The statistical checks (chi-square, normalisation) live in the Python harness.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "warp.h"

using namespace mcval;

namespace {

/// u values that break careless warps: both ends, the smallest float, one ulp from 1.
std::vector<float> hardValues() {
    return {0.f, std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(),
            1e-7f, 0.25f, 0.5f, 0.75f, kOneMinusEpsilon, 1.f};
}

std::vector<Vec2f> hardGrid() {
    std::vector<Vec2f> grid;
    for (float a : hardValues())
        for (float b : hardValues()) grid.emplace_back(a, b);
    return grid;
}

bool finite(const Vec3f &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void expectUnit(const Vec3f &v, const Vec2f &u) {
    EXPECT_TRUE(finite(v)) << "u = (" << u.x << ", " << u.y << ")";
    EXPECT_NEAR(norm(v), 1.f, 1e-5f) << "u = (" << u.x << ", " << u.y << ")";
}

void expectPositivePdf(float pdf, const Vec2f &u) {
    EXPECT_TRUE(std::isfinite(pdf) && pdf > 0.f)
        << "pdf = " << pdf << " at u = (" << u.x << ", " << u.y << ")";
}

}  // namespace

TEST(Warp, SquareAndTentStayInTheirSquares) {
    for (const Vec2f &u : hardGrid()) {
        const Vec2f s = squareToUniformSquare(u);
        EXPECT_EQ(squareToUniformSquarePdf(s), 1.f);
        const Vec2f t = squareToTent(u);
        EXPECT_LE(std::abs(t.x), 1.f);
        EXPECT_LE(std::abs(t.y), 1.f);
        expectPositivePdf(squareToTentPdf(t), u);
    }
    EXPECT_EQ(squareToTentPdf({1.01f, 0.f}), 0.f);
    EXPECT_EQ(squareToUniformSquarePdf({-0.01f, 0.5f}), 0.f);
}

/// The tent's inverse CDF as written in the seed and in Nori: a root on each side.
static float twoRootTent(float u) {
    u = std::min(std::max(u, kSampleFloor), kOneMinusEpsilon);
    return u < 0.5f ? std::sqrt(2.f * u) - 1.f : 1.f - std::sqrt(2.f - 2.f * u);
}

TEST(Warp, TentWithOneRootGivesTheBitsOfTheTwoRootForm) {
    // Every float in [1/4, 1] (where 1 - u and the sign of u - 1/2 matter), every 61st below, the
    // clamped values beyond and NaN.
    auto check = [](float u) {
        const float a = twoRootTent(u), b = detail::tentInverse(u);
        return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b));
    };
    size_t mismatches = 0, checked = 0;
    for (uint32_t bits = 0; bits <= 0x3f800000u; bits += bits < 0x3e800000u ? 61u : 1u, ++checked) {
        float u;
        std::memcpy(&u, &bits, sizeof u);
        mismatches += !check(u);
    }
    for (float u : {-1.f, -0.f, 1.5f, std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()})
        mismatches += !check(u);
    EXPECT_EQ(mismatches, 0u) << "of " << checked;
}

TEST(Warp, DiskStaysInTheDisk) {
    for (const Vec2f &u : hardGrid()) {
        const Vec2f d = squareToUniformDisk(u);
        EXPECT_LE(d.x * d.x + d.y * d.y, 1.f + kUnitTolerance);
        EXPECT_FLOAT_EQ(squareToUniformDiskPdf(d), kInvPi);
    }
    EXPECT_EQ(squareToUniformDiskPdf({0.8f, 0.8f}), 0.f);
}

TEST(Warp, SphereAndHemispheresGiveUnitVectors) {
    for (const Vec2f &u : hardGrid()) {
        expectUnit(squareToUniformSphere(u), u);
        const Vec3f h = squareToUniformHemisphere(u);
        expectUnit(h, u);
        EXPECT_GT(h.z, 0.f);
        expectPositivePdf(squareToUniformHemispherePdf(h), u);
        const Vec3f c = squareToCosineHemisphere(u);
        expectUnit(c, u);
        expectPositivePdf(squareToCosineHemispherePdf(c), u);
    }
    EXPECT_EQ(squareToUniformHemispherePdf({0.f, 0.6f, -0.8f}), 0.f);
    EXPECT_EQ(squareToCosineHemispherePdf({0.f, 0.6f, -0.8f}), 0.f);
}

TEST(Warp, BeckmannIsStableFromTinyToHugeAlpha) {
    for (float alpha : {1e-4f, 1e-3f, 1e-2f, 0.1f, 1.f, 10.f}) {
        for (const Vec2f &u : hardGrid()) {
            const Vec3f m = squareToBeckmann(u, alpha);
            expectUnit(m, u);
            EXPECT_GT(m.z, 0.f) << "alpha = " << alpha;
            expectPositivePdf(squareToBeckmannPdf(m, alpha), u);
        }
        EXPECT_EQ(squareToBeckmannPdf({1.f, 0.f, 0.f}, alpha), 0.f);
        EXPECT_EQ(squareToBeckmannPdf({1.f, 0.f, 1e-30f}, alpha), 0.f);
    }
}

TEST(Warp, BeckmannPdfIntegratesToOne) {
    // Midpoint rule in (cos theta, phi) with the azimuth integrated exactly
    // (the density is isotropic): integral = 2 pi * int_0^1 pdf(z) dz.
    for (float alpha : {0.05f, 0.3f, 1.f}) {
        const int n = 2000000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double z = (i + 0.5) / n;
            const float s = static_cast<float>(std::sqrt(1.0 - z * z));
            sum += squareToBeckmannPdf({s, 0.f, static_cast<float>(z)}, alpha);
        }
        EXPECT_NEAR(2.0 * M_PI * sum / n, 1.0, 2e-3) << "alpha = " << alpha;
    }
}

#include "sampler.h"

TEST(Sampler, EachPairIsStratifiedAndBatchesDiffer) {
    // 16 samples of one pair: exactly one in each of the 4 x 4 strata (a (0,2)-net).
    Sampler sampler(SamplerType::Sobol, 3, 0, 42);
    int counts[16] = {0};
    for (uint32_t i = 0; i < 16; ++i) {
        sampler.startSample(i);
        const Vec2f u = sampler.next2D();
        ASSERT_TRUE(u.x >= 0.f && u.x < 1.f && u.y >= 0.f && u.y < 1.f);
        ++counts[int(u.x * 4) * 4 + int(u.y * 4)];
    }
    for (int c : counts) EXPECT_EQ(c, 1);
    Sampler other(SamplerType::Sobol, 3, 1, 42);
    sampler.startSample(0);
    other.startSample(0);
    EXPECT_NE(sampler.next2D().x, other.next2D().x);
    EXPECT_EQ(detail::reverseBits(1u), 0x80000000u);
    EXPECT_EQ(detail::reverseBits(0x12345678u), 0x1E6A2C48u);
}

/// Fraction of `pixels` pixels whose first 16 samples fall one in each of the 4 x 4 strata.
static double stratifiedFraction(SamplerType type, int pixels) {
    int stratified = 0;
    for (int p = 0; p < pixels; ++p) {
        Sampler sampler(type, 7, 0, static_cast<uint64_t>(p));
        int counts[16] = {0};
        for (uint32_t i = 0; i < 16; ++i) {
            sampler.startSample(i);
            const Vec2f u = sampler.next2D();
            ++counts[int(u.x * 4) * 4 + int(u.y * 4)];
        }
        stratified += std::all_of(std::begin(counts), std::end(counts), [](int c) { return c == 1; });
    }
    return double(stratified) / pixels;
}

TEST(Sampler, IndependentIsUniformUncorrelatedAndNotStratified) {
    // One per stratum by chance has probability 16! / 16^16 = 1.1e-6; Sobol always is.
    EXPECT_EQ(stratifiedFraction(SamplerType::Sobol, 256), 1.0);
    EXPECT_EQ(stratifiedFraction(SamplerType::Independent, 4096), 0.0);
    // Moments over 2^16 values of two consecutive pairs: mean 1/2, variance 1/12, no correlation
    // between coordinates or between pairs (tolerances are 5 standard errors).
    const int n = 1 << 16;
    double sx = 0, sxx = 0, sxy = 0, sxz = 0;
    for (int k = 0; k < n; ++k) {
        Sampler sampler(SamplerType::Independent, 11, static_cast<uint64_t>(k % 8), static_cast<uint64_t>(k / 64));
        sampler.startSample(static_cast<uint32_t>(k % 64 / 8));
        const Vec2f a = sampler.next2D(), b = sampler.next2D();
        ASSERT_TRUE(a.x >= 0.f && a.x < 1.f && a.y >= 0.f && a.y < 1.f);
        sx += a.x;
        sxx += (a.x - 0.5) * (a.x - 0.5);
        sxy += (a.x - 0.5) * (a.y - 0.5);
        sxz += (a.x - 0.5) * (b.x - 0.5);
    }
    EXPECT_NEAR(sx / n, 0.5, 5 * std::sqrt(1.0 / 12 / n));
    EXPECT_NEAR(sxx / n, 1.0 / 12, 5 * std::sqrt(1.0 / 180 / n));
    EXPECT_NEAR(sxy / n, 0.0, 5 * (1.0 / 12) / std::sqrt(n));
    EXPECT_NEAR(sxz / n, 0.0, 5 * (1.0 / 12) / std::sqrt(n));
}

TEST(Sampler, NamesRoundTrip) {
    for (SamplerType t : {SamplerType::Independent, SamplerType::Sobol}) EXPECT_EQ(parseSampler(samplerName(t)), t);
    EXPECT_FALSE(parseSampler("multijitter").has_value());
}

TEST(Sampler, SobolTablesGiveTheBitwiseValues) {
    // The byte tables are the bitwise definition, for indices of every magnitude.
    uint32_t x = 12345u;
    for (int k = 0; k < 100000; ++k) {
        x = x * 1664525u + 1013904223u;
        const uint32_t index = k < 1024 ? static_cast<uint32_t>(k) : x;
        ASSERT_EQ(detail::sobolSecond(index), detail::sobolSecondBitwise(index)) << index;
    }
}

// The warps' own sin and cos of 2 pi v (sincos.h) against the library's in double, over [0, 1) and its
// quarter-turn boundaries, and the signs in one quadrant.
TEST(Warp, SinCos2PiMatchesTheLibraryWithinAFewUlps) {
    double worst = 0.0;
    const auto check = [&](float v) {
        float s, c;
        mcval::detail::sinCos2Pi(v, s, c);
        const double phi = 2.0 * 3.14159265358979323846 * double(v);
        worst = std::max({worst, std::abs(double(s) - std::sin(phi)), std::abs(double(c) - std::cos(phi))});
    };
    for (int i = 0; i < 1 << 20; ++i) check(float(i) / float(1 << 20));
    for (float q : {0.f, 0.125f, 0.25f, 0.375f, 0.5f, 0.625f, 0.75f, 0.875f, 1.f})
        for (float v : {q, std::nextafter(q, 0.f), std::nextafter(q, 1.f)}) check(v);
    check(mcval::kOneMinusEpsilon);
    EXPECT_LT(worst, 4e-7) << worst;  // a few ulps of 1 (a wrong quadrant or coefficient is off by far more)
    float s, c;
    mcval::detail::sinCos2Pi(0.3f, s, c);  // the second quadrant: sin > 0, cos < 0
    EXPECT_GT(s, 0.9f);
    EXPECT_LT(c, -0.3f);
}
