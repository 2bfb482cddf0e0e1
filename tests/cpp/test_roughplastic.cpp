// The rough plastic and its coating's tables: Gauss-Legendre quadrature exact on polynomials of degree 2n - 1; a
// nearly smooth coating transmits 1 - F and reflects the hemispherical Fresnel average from inside, as the smooth
// plastic's closed forms have it; on the hard inputs (alpha from 1e-4 to 1, wi on the normal and at grazing
// incidence, u at 0 and 1 - 2^-24) every value, weight and pdf finite and non-negative; every weight value / pdf.
// Its statistics against its pdf and Mitsuba's plugin are the BSDF checks' work (tests/bsdfs/test_roughplastic.py).
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "bsdfs/dielectric.h"
#include "bsdfs/plastic.h"
#include "bsdfs/roughplastic.h"
#include "warp.h"

using namespace mcval;

TEST(RoughPlastic, GaussLegendreIsExactOnPolynomialsOfDegreeTwoNMinusOne) {
    for (const int n : {1, 5, 32, 128}) {
        std::vector<double> nodes, weights;
        gaussLegendre(n, nodes, weights);
        double sum = 0.0, even = 0.0, odd = 0.0;
        const int degree = 2 * n - 2;  // the largest even degree within 2n - 1
        for (int i = 0; i < n; ++i) {
            sum += weights[i];
            even += weights[i] * std::pow(nodes[i], degree);
            odd += weights[i] * std::pow(nodes[i], degree + 1);
            if (i > 0) {
                EXPECT_LT(nodes[i - 1], nodes[i]);
            }
        }
        EXPECT_NEAR(sum, 2.0, 1e-12);
        EXPECT_NEAR(even, 2.0 / (degree + 1), 1e-12) << n;
        EXPECT_NEAR(odd, 0.0, 1e-12);
    }
}

TEST(RoughPlastic, ANearlySmoothCoatingHasTheSmoothPlasticsClosedForms) {
    const float eta = 1.5f;
    const auto coating = roughCoating(MicrofacetDistribution::Type::Beckmann, 1e-3f, eta);
    for (const float cosTheta : {1.f, 0.8f, 0.5f, 0.2f})
        EXPECT_NEAR(coating->transmittance(cosTheta), 1.f - fresnelDielectric(cosTheta, eta).reflectance, 2e-3f)
            << cosTheta;
    // The table's average over 64 cosines, as Mitsuba takes it: within a few hundredths of the exact integral.
    EXPECT_NEAR(coating->internalReflectance, fresnelDiffuseReflectance(1.f / eta), 0.02f);
    // A rough coating transmits more at grazing incidence: the microfacets light sees face it more squarely than
    // the macro-surface does, and Fresnel reflects less of it.
    EXPECT_GT(roughCoating(MicrofacetDistribution::Type::GGX, 0.5f, eta)->transmittance(0.1f),
              coating->transmittance(0.1f) + 0.1f);
}

TEST(RoughPlastic, HardInputsGiveNoNanAndNoNegative) {
    const float ends[] = {0.f, 0.5f, kOneMinusEpsilon};
    for (const auto type : {MicrofacetDistribution::Type::Beckmann, MicrofacetDistribution::Type::GGX})
        for (const bool visible : {false, true})
            for (const float alpha : {1e-4f, 0.1f, 1.f}) {
                const RoughPlasticBsdf bsdf(MicrofacetDistribution(type, alpha, visible), 1.5f, 1.f,
                                            Color(0.9f, 0.9f, 0.9f), true);
                for (const float cosTheta : {1.f, 0.5f, 0.0175f, 1e-6f, 0.f, -0.5f}) {
                    const Vec3f wi(std::sqrt(1.f - cosTheta * cosTheta), 0.f, cosTheta);
                    for (const float u1 : ends)
                        for (const float u2 : ends)
                            for (const float uLobe : ends) {
                                const BsdfSample s = bsdf.sample(wi, Vec2f(u1, u2), uLobe);
                                for (const float v : {s.weight.x, s.pdf}) EXPECT_TRUE(std::isfinite(v) && v >= 0.f);
                                EXPECT_NEAR(norm(s.wo), 1.f, 1e-4f);
                                if (s.pdf > 0.f) {
                                    EXPECT_GT(s.wo.z, 0.f);
                                    const float value = bsdf.eval(wi, s.wo).x;
                                    EXPECT_TRUE(std::isfinite(value) && value >= 0.f) << value;
                                }
                            }
                }
            }
}

TEST(RoughPlastic, TwoUniformsDrawBothLobesEachWeightValueOverPdf) {
    const RoughPlasticBsdf bsdf(MicrofacetDistribution(MicrofacetDistribution::Type::Beckmann, 0.1f, true), 1.5f, 1.f,
                                Color(0.5f, 0.5f, 0.5f), false);
    const Vec3f wi(std::sqrt(0.75f), 0.f, 0.5f);
    const Vec3f mirror(-wi.x, -wi.y, wi.z);
    constexpr int kSide = 100;
    int nearMirror = 0, drawn = 0;
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
            const BsdfSample s = bsdf.sample(wi, Vec2f((i + 0.5f) / kSide, (j + 0.5f) / kSide));
            if (s.pdf == 0.f) continue;
            ++drawn;
            nearMirror += dot(s.wo, mirror) > 0.95f;
            EXPECT_NEAR(s.weight.x, bsdf.eval(wi, s.wo).x / bsdf.pdf(wi, s.wo), 1e-4f * s.weight.x);
        }
    EXPECT_GT(drawn, kSide * kSide * 9 / 10);
    // The specular lobe takes (1 - T) / 1.5 against T / 3 of the choice at 60 degrees: some tenths, not all.
    EXPECT_GT(nearMirror, kSide * kSide / 20);
    EXPECT_LT(nearMirror, kSide * kSide * 3 / 4);
}
