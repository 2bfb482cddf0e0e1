// The rough dielectric on its hard inputs, from both sides: alpha from 1e-4 to 1, wi on the normal and at grazing
// incidence, u and the lobe's uniform at 0 and at 1 - 2^-24: every value, weight and pdf finite and non-negative,
// every sampled direction a unit vector; and with two uniforms (the lobe's hashed from them) both lobes drawn,
// each weight value / pdf (its statistics are the BSDF checks' work: tests/bsdfs/test_roughdielectric.py).
#include <cmath>

#include <gtest/gtest.h>

#include "bsdfs/roughdielectric.h"
#include "warp.h"

using namespace mcval;

namespace {

void expectSane(const Color &c) {
    for (const float v : {c.x, c.y, c.z}) EXPECT_TRUE(std::isfinite(v) && v >= 0.f) << v;
}

}  // namespace

TEST(RoughDielectric, HardInputsGiveNoNanAndNoNegativeFromBothSides) {
    const float ends[] = {0.f, 0.5f, kOneMinusEpsilon};
    for (const auto type : {MicrofacetDistribution::Type::Beckmann, MicrofacetDistribution::Type::GGX})
        for (const bool visible : {false, true})
            for (const float alpha : {1e-4f, 0.1f, 1.f}) {
                const RoughDielectricBsdf bsdf(MicrofacetDistribution(type, alpha, visible), 1.5f, 1.f);
                for (const float cosTheta : {1.f, 0.5f, 0.0175f, 1e-6f, -1.f, -0.5f, -0.0175f, -1e-6f}) {
                    const Vec3f wi(std::sqrt(1.f - cosTheta * cosTheta), 0.f, cosTheta);
                    for (const float u1 : ends)
                        for (const float u2 : ends)
                            for (const float uLobe : ends) {
                                const BsdfSample s = bsdf.sample(wi, Vec2f(u1, u2), uLobe);
                                expectSane(s.weight);
                                EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.f) << s.pdf;
                                EXPECT_NEAR(norm(s.wo), 1.f, 1e-4f);
                                if (s.pdf > 0.f) {
                                    expectSane(bsdf.eval(wi, s.wo));
                                    EXPECT_TRUE(std::isfinite(bsdf.pdf(wi, s.wo)));
                                }
                            }
                }
            }
}

TEST(RoughDielectric, TwoUniformsDrawBothLobesEachWeightValueOverPdf) {
    const RoughDielectricBsdf bsdf(MicrofacetDistribution(MicrofacetDistribution::Type::GGX, 0.3f, true), 1.5f, 1.f);
    const Vec3f wi(0.5f, 0.f, std::sqrt(0.75f));
    constexpr int kSide = 100;
    int reflected = 0, drawn = 0;
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
            const BsdfSample s = bsdf.sample(wi, Vec2f((i + 0.5f) / kSide, (j + 0.5f) / kSide));
            if (s.pdf == 0.f) continue;
            ++drawn;
            reflected += s.wo.z > 0.f;
            EXPECT_NEAR(s.weight.x, bsdf.eval(wi, s.wo).x / bsdf.pdf(wi, s.wo), 1e-3f * s.weight.x);
        }
    // Glass reflects about 4-5 % at 30 degrees: the hashed lobe uniform chooses reflection about that often.
    EXPECT_GT(drawn, kSide * kSide * 9 / 10);
    EXPECT_GT(reflected, drawn * 2 / 100);
    EXPECT_LT(reflected, drawn * 10 / 100);
}
