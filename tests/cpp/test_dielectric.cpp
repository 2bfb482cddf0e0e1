// The smooth dielectric against closed forms: Fresnel's ((eta - 1) / (eta + 1))^2 at normal incidence from either
// side, 1 beyond the critical angle from inside, 0 for matched indices; refracted directions unit vectors at
// Snell's angle (its statistics and Mitsuba's agreement are the BSDF checks' work: tests/bsdfs/test_dielectric.py).
#include <cmath>

#include <gtest/gtest.h>

#include "bsdfs/dielectric.h"
#include "warp.h"

using namespace mcval;

TEST(Dielectric, FresnelMeetsItsClosedForms) {
    const float normal = (0.5f / 2.5f) * (0.5f / 2.5f);
    EXPECT_NEAR(fresnelDielectric(1.f, 1.5f).reflectance, normal, 1e-6f);
    EXPECT_NEAR(fresnelDielectric(-1.f, 1.5f).reflectance, normal, 1e-6f);
    const float critical = std::sqrt(1.f - 1.f / (1.5f * 1.5f));  // cos theta of the critical angle, inside
    EXPECT_EQ(fresnelDielectric(-0.9f * critical, 1.5f).reflectance, 1.f);
    EXPECT_EQ(fresnelDielectric(0.3f, 1.f).reflectance, 0.f);
    EXPECT_EQ(fresnelDielectric(0.f, 1.5f).reflectance, 1.f);  // grazing: all reflected, no 0 / 0
}

TEST(Dielectric, RefractionIsAUnitVectorAtSnellsAngleAndHardInputsAreSafe) {
    const DielectricBsdf glass(1.5f, 1.f);
    for (const float cosTheta : {1.f, 0.5f, 1e-6f, -1e-6f, -0.5f, -1.f})
        for (const float u : {0.f, 0.5f, kOneMinusEpsilon}) {
            const Vec3f wi(std::sqrt(1.f - cosTheta * cosTheta), 0.f, cosTheta);
            const BsdfSample s = glass.sample(wi, Vec2f(u, 0.f));
            EXPECT_TRUE(std::isinf(s.pdf) && s.pdf > 0.f);
            EXPECT_TRUE(std::isfinite(s.weight.x) && s.weight.x > 0.f) << s.weight.x;
            EXPECT_NEAR(norm(s.wo), 1.f, 1e-5f);
            if (s.wo.z * wi.z < 0.f) {  // refracted: sin theta_o = sin theta_i * eta_ti
                const float etaTi = cosTheta > 0.f ? 1.f / 1.5f : 1.5f;
                EXPECT_NEAR(std::hypot(s.wo.x, s.wo.y), etaTi * wi.x, 1e-6f);
                EXPECT_NEAR(s.weight.x, etaTi * etaTi, 1e-6f);
            }
        }
}
