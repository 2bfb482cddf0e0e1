// ImageBlock::putPacket's gaussian splat (a packet of a pixel's samples at once) against the
// reference put() per sample: the same 11 sums per pixel, to rounding.
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "film.h"

using namespace mcval;

namespace {

FilterSpec gaussian(float stddev) {
    FilterSpec f;
    f.type = FilterSpec::Type::Gaussian;
    f.stddev = stddev;
    return f;
}

/// Largest relative difference of the two blocks' sums over every pixel and channel.
double maxRelativeDifference(const ImageBlock &a, const ImageBlock &b) {
    double worst = 0.0;
    for (int j = 0; j < a.height(); ++j)
        for (int i = 0; i < a.width(); ++i)
            for (int c = 0; c < ImageBlock::kChannels; ++c) {
                const double x = a.sums(i, j)[c], y = b.sums(i, j)[c];
                const double d = std::abs(x - y) / std::max({std::abs(x), std::abs(y), 1e-300});
                worst = std::max(worst, x == y ? 0.0 : d);
            }
    return worst;
}

/// Puts `packets` random packets (1..16 samples, random positions inside random pixels of the tile,
/// random colours) through putPacket into `packet` and through put() per sample into `single`;
/// `shift` moves the positions put() gets (a wrong reference, which must then differ).
void fill(ImageBlock &packet, ImageBlock &single, int x0, int y0, int w, int h, int packets, unsigned seed,
          float shift = 0.f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    std::uniform_int_distribution<int> px(x0, x0 + w - 1), py(y0, y0 + h - 1), n(1, ImageBlock::kMaxPacket);
    for (int p = 0; p < packets; ++p) {
        // Every pixel of the tile's border first (the footprints reaching the block's edge), then at random.
        const int edge = 2 * (w + h);
        int x, y;
        if (p < edge) {
            const int e = p % (w + h);
            x = e < w ? x0 + e : (p < w + h ? x0 : x0 + w - 1);
            y = e < w ? (p < w + h ? y0 : y0 + h - 1) : y0 + (e - w) % h;
        } else {
            x = px(rng);
            y = py(rng);
        }
        const int count = p % 3 == 0 ? ImageBlock::kMaxPacket : n(rng);
        float fx[ImageBlock::kMaxPacket], fy[ImageBlock::kMaxPacket];
        Color L[ImageBlock::kMaxPacket];
        for (int k = 0; k < count; ++k) {
            fx[k] = static_cast<float>(x) + u(rng);
            fy[k] = static_cast<float>(y) + u(rng);
            // Some samples at the pixel's corner and centre (weights of exactly 0 at the radius).
            if (k == 1 && p % 5 == 0) fx[k] = static_cast<float>(x), fy[k] = static_cast<float>(y);
            if (k == 2 && p % 7 == 0) fx[k] = static_cast<float>(x) + 0.5f, fy[k] = static_cast<float>(y) + 0.5f;
            L[k] = Color{u(rng), 2.f * u(rng), u(rng) < 0.2f ? 0.f : 10.f * u(rng)};
        }
        packet.putPacket(x, y, fx, fy, L, count);
        for (int k = 0; k < count; ++k) single.put(fx[k] + shift, fy[k], L[k]);
    }
}

}  // namespace

TEST(Film, GaussianPacketMatchesPutPerSample) {
    // Mitsuba's default (stddev 0.5, radius 2), narrower and wider ones, and radius 1.5, whose window
    // (x +- 2) is wider than the block's border (1): the taps outside have weight 0.
    for (const float stddev : {0.5f, 0.3f, 0.375f, 0.45f, 1.1f, 0.05f}) {
        // A tile at the image's top-left corner, one inside, and a small one at the edge.
        for (const auto &[x0, y0, w, h] : std::vector<std::array<int, 4>>{{0, 0, 16, 16}, {48, 32, 16, 8}, {125, 0, 3, 2}}) {
            const FilterSpec f = gaussian(stddev);
            ImageBlock packet(x0, y0, w, h, f), single(x0, y0, w, h, f);
            fill(packet, single, x0, y0, w, h, 3000, 7u + static_cast<unsigned>(x0));
            EXPECT_LT(maxRelativeDifference(packet, single), 1e-5) << "stddev " << stddev << " tile " << x0 << "," << y0;
            // Every pixel the samples reach has its sums (the border too).
            EXPECT_GT(packet.sums(0, 0)[0], 0.0);
            EXPECT_GT(packet.sums(packet.width() - 1, packet.height() - 1)[0], 0.0);
        }
    }
}

TEST(Film, TentPacketMatchesPutPerSample) {
    // Mitsuba's default radius (1), a wider one, one narrower than a pixel, and the widest allowed.
    for (const float radius : {1.f, 1.25f, 2.7f, 0.3f, 16.f}) {
        FilterSpec f;
        f.type = FilterSpec::Type::Tent;
        f.tentRadius = radius;
        for (const auto &[x0, y0, w, h] : std::vector<std::array<int, 4>>{{0, 0, 16, 16}, {125, 0, 3, 2}}) {
            ImageBlock packet(x0, y0, w, h, f), single(x0, y0, w, h, f);
            fill(packet, single, x0, y0, w, h, 1000, 5u + static_cast<unsigned>(x0));
            EXPECT_LT(maxRelativeDifference(packet, single), 1e-5) << "radius " << radius << " tile " << x0;
        }
    }
}

TEST(Film, TentWeightsAreMitsubas) {
    // tent.cpp: max(0, 1 - |x| / radius), separable: one sample at a pixel's centre, radius 2, gives the
    // pixel weight 1, its neighbours 1/2 along an axis and 1/4 diagonally, the next ones 0.
    FilterSpec f;
    f.type = FilterSpec::Type::Tent;
    f.tentRadius = 2.f;
    ImageBlock block(4, 4, 1, 1, f);
    block.put(4.5f, 4.5f, Color{1.f, 1.f, 1.f});
    const int b = 4 - block.x0();  // the block's index of pixel 4
    EXPECT_EQ(block.sums(b, b)[0], 1.0);
    EXPECT_EQ(block.sums(b + 1, b)[0], 0.5);
    EXPECT_EQ(block.sums(b - 1, b - 1)[0], 0.25);
    EXPECT_EQ(block.sums(b + 2, b)[0], 0.0);  // in the border (ceil(2 - 0.5) = 2 wide), at the radius
}

TEST(Film, GaussianPacketCheckDetectsAShiftedSample) {
    // The twin of the test above with a wrong reference: the check must fail.
    const FilterSpec f = gaussian(0.5f);
    ImageBlock packet(0, 0, 16, 16, f), single(0, 0, 16, 16, f);
    fill(packet, single, 0, 0, 16, 16, 300, 3u, 0.01f);
    EXPECT_GT(maxRelativeDifference(packet, single), 1e-3);
}

TEST(Film, GaussianPacketIsDeterministic) {
    const FilterSpec f = gaussian(0.5f);
    ImageBlock a(16, 16, 16, 16, f), b(16, 16, 16, 16, f), ra(16, 16, 16, 16, f), rb(16, 16, 16, 16, f);
    fill(a, ra, 16, 16, 16, 16, 500, 11u);
    fill(b, rb, 16, 16, 16, 16, 500, 11u);
    EXPECT_EQ(maxRelativeDifference(a, b), 0.0);
}

TEST(Film, GaussianPacketWithANonFiniteSampleMatchesPut) {
    // A non-finite sample reaches only the pixels of non-zero weight, as put() does.
    const FilterSpec f = gaussian(0.5f);
    ImageBlock packet(0, 0, 8, 8, f), single(0, 0, 8, 8, f);
    float fx[3] = {3.2f, 3.9f, 3.5f}, fy[3] = {4.1f, 4.6f, 4.0f};
    const Color L[3] = {{1.f, 2.f, 3.f}, {INFINITY, 0.f, 1.f}, {0.5f, NAN, 0.f}};
    packet.putPacket(3, 4, fx, fy, L, 3);
    for (int k = 0; k < 3; ++k) single.put(fx[k], fy[k], L[k]);
    for (int j = 0; j < packet.height(); ++j)
        for (int i = 0; i < packet.width(); ++i)
            for (int c = 0; c < ImageBlock::kChannels; ++c) {
                const double x = packet.sums(i, j)[c], y = single.sums(i, j)[c];
                EXPECT_TRUE((std::isnan(x) && std::isnan(y)) || x == y) << i << "," << j << "," << c;
            }
}

TEST(Film, ExpNonPositiveIsWithinTwoUlp) {
    // Over the range the gaussian's weights use (down to -87, below which it clamps).
    float worst = 0.f;
    for (float x = -87.f; x <= 0.f; x += 0.00137f) {
        const double exact = std::exp(static_cast<double>(x));
        const float got = expNonPositive(x);
        const double ulp = std::nextafter(static_cast<float>(exact), INFINITY) - static_cast<float>(exact);
        worst = std::max(worst, static_cast<float>(std::abs(got - exact) / ulp));
    }
    EXPECT_LE(worst, 2.f);
    EXPECT_EQ(expNonPositive(0.f), 1.f);
    EXPECT_GT(expNonPositive(-1000.f), 0.f);
    EXPECT_LT(expNonPositive(-1000.f), 1e-37f);
}
