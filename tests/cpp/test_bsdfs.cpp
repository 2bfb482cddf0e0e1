// The BSDF models: sample's pdf is pdf() at the sampled direction and its weight is eval / pdf; the
// energy a Monte Carlo estimate draws (the mean weight) is the albedo; the twosided one answers from
// behind with its back; and wrong twins (a pdf without its cosine, an eval without the cosine) fail.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "bsdfs/diffuse.h"
#include "bsdfs/twosided.h"
#include "warp.h"

using namespace mcval;

namespace {

struct Uniforms {
    std::mt19937 rng;
    explicit Uniforms(uint32_t seed) : rng(seed) {}
    float next() { return float(rng() >> 8) * 0x1p-24f; }
    Vec2f next2D() { return {next(), next()}; }
};

bool same(const Color &a, const Color &b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

bool close(float a, float b) { return std::abs(a - b) <= 1e-4f * std::max(std::abs(a), std::abs(b)) + 1e-7f; }

/// Samples from wi whose pdf is not pdf() at their direction or whose weight is not eval / pdf there.
int sampleMismatches(const Bsdf &bsdf, const Vec3f &wi, int n) {
    Uniforms u(5);
    int bad = 0;
    for (int k = 0; k < n; ++k) {
        const BsdfSample s = bsdf.sample(wi, u.next2D());
        if (!(s.pdf > 0.f)) {
            bad += s.weight.x != 0.f;
            continue;
        }
        const Color f = bsdf.eval(wi, s.wo);
        bad += !close(bsdf.pdf(wi, s.wo), s.pdf) || !close(f.x / s.pdf, s.weight.x) || !close(f.z / s.pdf, s.weight.z);
    }
    return bad;
}

/// The mean of the sample weights: the hemispherical-directional reflectance seen from wi.
Color energy(const Bsdf &bsdf, const Vec3f &wi, int n) {
    Uniforms u(6);
    Color sum(0.f, 0.f, 0.f);
    for (int k = 0; k < n; ++k) sum = sum + bsdf.sample(wi, u.next2D()).weight;
    return sum / float(n);
}

/// The integral of eval over the sphere by uniform sampling: the energy eval alone gives (no sampler).
Color evalEnergy(const Bsdf &bsdf, const Vec3f &wi, int n) {
    Uniforms u(7);
    Color sum(0.f, 0.f, 0.f);
    for (int k = 0; k < n; ++k) {
        const Vec3f wo = squareToUniformSphere(u.next2D());
        sum = sum + bsdf.eval(wi, wo) / squareToUniformSpherePdf(wo);
    }
    return sum / float(n);
}

/// A diffuse BSDF whose eval forgets the cosine (f alone), its sampler right: eval / pdf is not the weight.
class NoCosineTwin final : public Bsdf {
public:
    explicit NoCosineTwin(const Color &rho) : m_right(rho) {}
    Color eval(const Vec3f &wi, const Vec3f &wo) const override {
        const Color f = m_right.eval(wi, wo);
        return wo.z > 0.f ? f / wo.z : f;
    }
    float pdf(const Vec3f &wi, const Vec3f &wo) const override { return m_right.pdf(wi, wo); }
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override { return m_right.sample(wi, u); }
    std::optional<Color> lambertianAlbedo(bool front) const override { return m_right.lambertianAlbedo(front); }

private:
    DiffuseBsdf m_right;
};

/// A diffuse BSDF whose pdf is uniform over the hemisphere while it samples by the cosine.
class UniformPdfTwin final : public Bsdf {
public:
    explicit UniformPdfTwin(const Color &rho) : m_right(rho) {}
    Color eval(const Vec3f &wi, const Vec3f &wo) const override { return m_right.eval(wi, wo); }
    float pdf(const Vec3f &wi, const Vec3f &wo) const override {
        return wi.z > 0.f && wo.z > 0.f ? kInv2Pi : 0.f;
    }
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override { return m_right.sample(wi, u); }
    std::optional<Color> lambertianAlbedo(bool front) const override { return m_right.lambertianAlbedo(front); }

private:
    DiffuseBsdf m_right;
};

const Vec3f kWi = normalize(Vec3f(0.3f, -0.2f, 0.8f));

}  // namespace

TEST(Bsdfs, DiffuseSamplesMatchItsPdfAndEval) {
    const DiffuseBsdf diffuse({0.2f, 0.5f, 0.9f});
    EXPECT_EQ(sampleMismatches(diffuse, kWi, 5000), 0);
    EXPECT_EQ(sampleMismatches(diffuse, {0.f, 0.f, 1.f}, 5000), 0);
    // Mitsuba's values: rho / pi cos theta_o, the cosine hemisphere's pdf, black below either side.
    const Vec3f wo = normalize(Vec3f(-0.1f, 0.4f, 0.6f));
    EXPECT_FLOAT_EQ(diffuse.eval(kWi, wo).y, 0.5f * kInvPi * wo.z);
    EXPECT_FLOAT_EQ(diffuse.pdf(kWi, wo), wo.z * kInvPi);
    EXPECT_EQ(diffuse.eval(kWi, {wo.x, wo.y, -wo.z}).y, 0.f);
    EXPECT_EQ(diffuse.eval({kWi.x, kWi.y, -kWi.z}, wo).y, 0.f);
    EXPECT_EQ(diffuse.pdf({kWi.x, kWi.y, -kWi.z}, wo), 0.f);
    // From behind a one-sided diffuse surface nothing is sampled.
    const BsdfSample behind = diffuse.sample({kWi.x, kWi.y, -kWi.z}, {0.3f, 0.3f});
    EXPECT_EQ(behind.weight.x, 0.f);
    EXPECT_EQ(behind.pdf, 0.f);
}

TEST(Bsdfs, DiffuseEnergyIsItsAlbedo) {
    const Color rho{0.2f, 0.5f, 0.9f};
    const DiffuseBsdf diffuse(rho);
    const Color sampled = energy(diffuse, kWi, 1000);
    EXPECT_NEAR(sampled.x, rho.x, 1e-5f);  // cosine sampling: every weight is rho
    EXPECT_NEAR(sampled.z, rho.z, 1e-5f);
    const Color integrated = evalEnergy(diffuse, kWi, 400000);
    EXPECT_NEAR(integrated.y, rho.y, 0.01f * rho.y);
    EXPECT_NEAR(integrated.z, rho.z, 0.01f * rho.z);
    EXPECT_TRUE(same(*diffuse.lambertianAlbedo(true), rho));
    EXPECT_EQ(diffuse.lambertianAlbedo(false)->x, 0.f);
    EXPECT_FALSE(diffuse.twoSided());
}

TEST(Bsdfs, WrongTwinsFailTheSameChecks) {
    const Color rho{0.2f, 0.5f, 0.9f};
    EXPECT_GT(sampleMismatches(NoCosineTwin(rho), kWi, 2000), 1900);
    EXPECT_GT(sampleMismatches(UniformPdfTwin(rho), kWi, 2000), 1900);
    // Without its cosine, eval's energy is twice the albedo.
    EXPECT_GT(evalEnergy(NoCosineTwin(rho), kWi, 100000).z, 1.5f * rho.z);
}

TEST(Bsdfs, TwosidedAnswersFromBehindWithItsBack) {
    const auto front = std::make_shared<DiffuseBsdf>(Color(0.3f, 0.3f, 0.3f));
    const auto back = std::make_shared<DiffuseBsdf>(Color(0.7f, 0.1f, 0.2f));
    const TwoSidedBsdf both(front, back);
    EXPECT_TRUE(both.twoSided());
    EXPECT_TRUE(same(*both.lambertianAlbedo(true), Color(0.3f, 0.3f, 0.3f)));
    EXPECT_TRUE(same(*both.lambertianAlbedo(false), Color(0.7f, 0.1f, 0.2f)));
    const Vec3f below{kWi.x, kWi.y, -kWi.z};
    EXPECT_EQ(sampleMismatches(both, kWi, 2000), 0);
    EXPECT_EQ(sampleMismatches(both, below, 2000), 0);
    // From behind, the sampled directions lie behind too, and the back's albedo is the energy.
    Uniforms u(3);
    for (int k = 0; k < 100; ++k) EXPECT_LT(both.sample(below, u.next2D()).wo.z, 0.f);
    EXPECT_FLOAT_EQ(energy(both, below, 100).x, 0.7f);
    const Vec3f wo = normalize(Vec3f(0.1f, 0.2f, -0.7f));
    EXPECT_FLOAT_EQ(both.eval(below, wo).x, 0.7f * kInvPi * -wo.z);
    EXPECT_EQ(both.eval(below, {wo.x, wo.y, -wo.z}).x, 0.f);  // through the surface: nothing
    EXPECT_FLOAT_EQ(both.pdf(below, wo), -wo.z * kInvPi);
}
