// The rough conductor on its hard inputs: alpha from 1e-4 to 1, wi on the normal and at grazing incidence,
// u at 0 and at 1 - 2^-24: every value, weight and pdf finite and non-negative, every sampled direction a
// unit vector (its statistics are the BSDF checks' work: tests/bsdfs/test_roughconductor.py).
#include <cmath>

#include <gtest/gtest.h>

#include "bsdfs/roughconductor.h"
#include "warp.h"

using namespace mcval;

namespace {

void expectSane(const Color &c) {
    for (const float v : {c.x, c.y, c.z}) EXPECT_TRUE(std::isfinite(v) && v >= 0.f) << v;
}

}  // namespace

TEST(RoughConductor, HardInputsGiveNoNanAndNoNegative) {
    const float ends[] = {0.f, 0.5f, kOneMinusEpsilon};
    for (const auto type : {MicrofacetDistribution::Type::Beckmann, MicrofacetDistribution::Type::GGX})
        for (const bool visible : {false, true})
            for (const float alpha : {1e-4f, 0.1f, 1.f}) {
                const RoughConductorBsdf bsdf(MicrofacetDistribution(type, alpha, visible), 0.2f, 3.f, Color(1, 1, 1));
                for (const float cosTheta : {1.f, 0.5f, 0.0175f, 1e-6f}) {
                    const Vec3f wi(std::sqrt(1.f - cosTheta * cosTheta), 0.f, cosTheta);
                    for (const float u1 : ends)
                        for (const float u2 : ends) {
                            const BsdfSample s = bsdf.sample(wi, Vec2f(u1, u2));
                            expectSane(s.weight);
                            EXPECT_TRUE(std::isfinite(s.pdf) && s.pdf >= 0.f) << s.pdf;
                            if (s.pdf > 0.f) {
                                EXPECT_NEAR(norm(s.wo), 1.f, 1e-4f);
                                expectSane(bsdf.eval(wi, s.wo));
                                EXPECT_TRUE(std::isfinite(bsdf.pdf(wi, s.wo)));
                            }
                        }
                }
            }
}

TEST(RoughConductor, FresnelOfAConductorIsItsReflectanceAtNormalIncidence) {
    // ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2) at cos theta = 1, and 1 at grazing incidence.
    const float eta = 0.2f, k = 3.f;
    EXPECT_NEAR(fresnelConductor(1.f, eta, k), ((eta - 1) * (eta - 1) + k * k) / ((eta + 1) * (eta + 1) + k * k), 1e-6f);
    EXPECT_NEAR(fresnelConductor(0.f, eta, k), 1.f, 1e-6f);
}
