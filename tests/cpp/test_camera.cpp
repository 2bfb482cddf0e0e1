// Camera rays follow Mitsuba's perspective conventions.
#include <cmath>

#include <gtest/gtest.h>

#include "camera.h"

using namespace mcval;

namespace {
CameraSpec lookingDownMinusZ(float fov, const std::string &axis) {
    CameraSpec spec;
    spec.fov = fov;
    spec.fovAxis = axis;
    spec.toWorld = Transform::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0});
    return spec;
}

float angleDegrees(const Vec3f &a, const Vec3f &b) {
    return std::acos(std::max(-1.f, std::min(1.f, dot(normalize(a), normalize(b))))) * 180.f / 3.14159265f;
}
}  // namespace

TEST(Camera, CentreRayLooksAtTheTarget) {
    const Camera cam(lookingDownMinusZ(40.f, "x"), 64, 48);
    const Ray r = cam.generateRay(32.f, 24.f);
    EXPECT_NEAR(r.d.x, 0.f, 1e-6f);
    EXPECT_NEAR(r.d.y, 0.f, 1e-6f);
    EXPECT_NEAR(r.d.z, -1.f, 1e-6f);
}

TEST(Camera, EdgeRaysSpanTheFov) {
    const Camera cam(lookingDownMinusZ(40.f, "x"), 64, 48);
    const Vec3f forward(0, 0, -1);
    EXPECT_NEAR(angleDegrees(cam.generateRay(0.f, 24.f).d, forward), 20.f, 1e-3f);
    EXPECT_NEAR(angleDegrees(cam.generateRay(64.f, 24.f).d, forward), 20.f, 1e-3f);
    // The image is not mirrored: its left edge looks to the viewer's left (-x here), its top up.
    EXPECT_LT(cam.generateRay(0.f, 24.f).d.x, 0.f);
    EXPECT_GT(cam.generateRay(32.f, 0.f).d.y, 0.f);
    // Vertical extent follows the aspect ratio: tan(v/2) = tan(20 deg) * 48 / 64.
    const float v = 2.f * std::atan(std::tan(20.f * 3.14159265f / 180.f) * 48.f / 64.f) * 180.f / 3.14159265f;
    EXPECT_NEAR(angleDegrees(cam.generateRay(32.f, 0.f).d, forward), v / 2.f, 1e-3f);
}

TEST(Camera, FovAxisYIsVertical) {
    const Camera cam(lookingDownMinusZ(30.f, "y"), 64, 48);
    EXPECT_NEAR(angleDegrees(cam.generateRay(32.f, 0.f).d, {0, 0, -1}), 15.f, 1e-3f);
    EXPECT_NEAR(angleDegrees(cam.generateRay(32.f, 48.f).d, {0, 0, -1}), 15.f, 1e-3f);
}

TEST(Camera, RaysStartAtTheNearClipPlane) {
    CameraSpec spec = lookingDownMinusZ(40.f, "x");
    spec.nearClip = 0.5f;
    const Camera cam(spec, 64, 48);
    const Ray r = cam.generateRay(0.f, 0.f);
    // The start point lies on the plane z = 5 - 0.5, whatever the ray's angle.
    EXPECT_NEAR(r.o.z + r.tnear * r.d.z, 4.5f, 1e-5f);
}
