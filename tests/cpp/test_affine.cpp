// The double-precision affine map of the exact shapes (renderer/affine.h).
#include <gtest/gtest.h>

#include "affine.h"

using namespace mcval;

TEST(Affine, ItsInverseUndoesItAndAProductAppliesTheRightFactorFirst) {
    const float m[16] = {2, 0.5f, -1, 3, 0.25f, -1.5f, 0.75f, -2, 1, 2, 4, 0.5f, 0, 0, 0, 1};
    const Affine f = Affine::from(Transform(m));
    const Affine g = Affine::fromColumns({0, 1, 0}, {-2, 0, 0}, {0, 0, 3}, {1, 1, 1});
    const Vec3d p{0.3, -1.7, 2.9};
    const Vec3d back = f.inversePoint(f.point(p));
    EXPECT_NEAR(back.x, p.x, 1e-14); EXPECT_NEAR(back.y, p.y, 1e-14); EXPECT_NEAR(back.z, p.z, 1e-14);
    const Vec3d fg = (f * g).point(p), expected = f.point(g.point(p));
    EXPECT_NEAR(fg.x, expected.x, 1e-13); EXPECT_NEAR(fg.y, expected.y, 1e-13); EXPECT_NEAR(fg.z, expected.z, 1e-13);
    // The normal transform keeps normals perpendicular to transformed tangents.
    const Vec3d n = f.normal({0, 0, 1});
    EXPECT_NEAR(dot(n, f.vector({1, 0, 0})), 0.0, 1e-14);
    EXPECT_NEAR(dot(n, f.vector({0, 1, 0})), 0.0, 1e-14);
    EXPECT_FALSE(isDegenerate(f));
    EXPECT_TRUE(isDegenerate(Affine::fromColumns({1, 0, 0}, {1, 1e-7, 0}, {0, 0, 1}, {})));
}
