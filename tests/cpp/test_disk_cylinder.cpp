// The exact disk and cylinder: hits and misses where Mitsuba 3 puts them (its values, checked with its
// ray_intersect), normals and flip_normals as it orients them, single rays and packets agreeing, hit
// points on the surface far from the origin, the loaders' checks, and finite renders.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "embree_scene.h"
#include "error.h"
#include "image_counts.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

std::string writeScene(const std::string &name, const std::string &body) {
    const fs::path path = fs::temp_directory_path() / ("mcval_disk_cylinder_" + name + ".xml");
    std::ofstream(path) << body;
    return path.string();
}

/// A scene of one shape of `type` with `shapeBody` inside, seen from +z.
std::string shapeScene(const std::string &type, const std::string &shapeBody) {
    return "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"60\"/>"
           "<transform name=\"to_world\"><lookat origin=\"0.3, 0.2, 5\" target=\"0, 0, 0.5\"/></transform>"
           "<film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"24\"/>"
           "</film></sensor>\n<shape type=\"" + type + "\">\n" + shapeBody +
           "</shape>\n<emitter type=\"point\"><point name=\"position\" value=\"2, 3, 4\"/>"
           "<rgb name=\"intensity\" value=\"20\"/></emitter>\n</scene>\n";
}

SceneDescription load(const std::string &name, const std::string &type, const std::string &body) {
    return loadScene(writeScene(name, shapeScene(type, body)));
}

std::string errorOf(const std::string &name, const std::string &type, const std::string &body) {
    try {
        load(name, type, body);
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

/// The scene's shapes in an EmbreeScene, traced one ray at a time and as a packet (the camera's path).
struct Traced {
    SceneDescription scene;
    EmbreeScene embree;
    explicit Traced(SceneDescription s)
        : scene(std::move(s)), embree(scene.meshes, scene.spheres, scene.disks, scene.cylinders, scene.bsdfs) {}

    /// The hit of the ray from o along d; both paths must agree on it.
    bool trace(const Vec3f &o, const Vec3f &d, Hit &hit) const {
        Ray ray;
        ray.o = o;
        ray.d = normalize(d);
        ray.tnear = 0.f;
        ray.tfar = 1e4f;
        const bool found = embree.intersect(ray, hit);
        RayHitPacket packet;
        packet.set(0, true, ray.o, ray.d, ray.tnear, ray.tfar);
        HitPacket lanes;
        embree.intersect(packet, 1, lanes);
        EXPECT_EQ(found, lanes.found[0] != 0);
        EXPECT_EQ(found, embree.occluded(ray));
        if (found) {
            const Hit h = lanes.hit(0);
            EXPECT_EQ(h.p.x, hit.p.x); EXPECT_EQ(h.p.y, hit.p.y); EXPECT_EQ(h.p.z, hit.p.z);
            EXPECT_EQ(h.ns.x, hit.ns.x); EXPECT_EQ(h.ns.y, hit.ns.y); EXPECT_EQ(h.ns.z, hit.ns.z);
        }
        return found;
    }
};

void expectNear(const Vec3f &a, const Vec3f &b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

const std::string kStretchedDisk =  // an ellipse of semi-axes 2 (x) and 1 (y), at z = 0.5
    "<transform name=\"to_world\"><scale value=\"2, 1, 3\"/><translate value=\"0, 0, 0.5\"/></transform>\n";

}  // namespace

TEST(Disk, HitsInsideItsEllipseFromBothSidesWithTheNormalOfToWorld) {
    const Traced t(load("disk", "disk", kStretchedDisk));
    ASSERT_EQ(t.scene.disks.size(), 1u);
    Hit hit;
    ASSERT_TRUE(t.trace({1.5f, 0.2f, 5.f}, {0.f, 0.f, -1.f}, hit));
    EXPECT_NEAR(hit.t, 4.5f, 1e-5f);
    expectNear(hit.p, {1.5f, 0.2f, 0.5f}, 1e-6f);
    expectNear(hit.ns, {0.f, 0.f, 1.f}, 1e-7f);
    expectNear(hit.ng, hit.ns, 0.f);
    // From behind: hit too, the normal still +z (the front is where it points; Mitsuba does not turn it).
    ASSERT_TRUE(t.trace({1.5f, 0.2f, -5.f}, {0.f, 0.f, 1.f}, hit));
    expectNear(hit.ns, {0.f, 0.f, 1.f}, 1e-7f);
    // Outside the ellipse: x = 1.5 is inside along x (semi-axis 2), y = 1.1 is not (semi-axis 1).
    EXPECT_FALSE(t.trace({0.f, 1.1f, 5.f}, {0.f, 0.f, -1.f}, hit));
    EXPECT_FALSE(t.trace({1.9f, 0.5f, 5.f}, {0.f, 0.f, -1.f}, hit));
    // Parallel to its plane, and pointing away: no hit.
    EXPECT_FALSE(t.trace({-5.f, 0.f, 0.5f}, {1.f, 0.f, 0.f}, hit));
    EXPECT_FALSE(t.trace({0.f, 0.f, 5.f}, {0.f, 0.f, 1.f}, hit));
}

TEST(Disk, APlantedWrongScaleMissesWhereTheRightOneHits) {
    Hit hit;
    EXPECT_TRUE(Traced(load("disk_right", "disk", kStretchedDisk)).trace({1.5f, 0.f, 5.f}, {0.f, 0.f, -1.f}, hit));
    EXPECT_FALSE(Traced(load("disk_wrong", "disk", "<transform name=\"to_world\"><translate value=\"0, 0, 0.5\"/>"
                                                 "</transform>\n"))
                     .trace({1.5f, 0.f, 5.f}, {0.f, 0.f, -1.f}, hit));
}

TEST(Disk, FlipNormalsAMirroredZAndARotationTurnTheNormal) {
    Hit hit;
    const Traced flipped(load("disk_flip", "disk", "<boolean name=\"flip_normals\" value=\"true\"/>\n"));
    ASSERT_TRUE(flipped.trace({0.3f, 0.2f, 5.f}, {0.f, 0.f, -1.f}, hit));
    expectNear(hit.ns, {0.f, 0.f, -1.f}, 1e-7f);
    const Traced mirrored(load("disk_mirror", "disk", "<transform name=\"to_world\"><scale value=\"1, 1, -1\"/>"
                                                      "</transform>\n"));
    ASSERT_TRUE(mirrored.trace({0.3f, 0.2f, 5.f}, {0.f, 0.f, -1.f}, hit));
    expectNear(hit.ns, {0.f, 0.f, -1.f}, 1e-7f);
    // A mirrored x keeps +z, as in Mitsuba (its normal is to_world's inverse transpose of +z).
    const Traced mirroredX(load("disk_mirror_x", "disk", "<transform name=\"to_world\"><scale value=\"-1, 1, 1\"/>"
                                                         "</transform>\n"));
    ASSERT_TRUE(mirroredX.trace({0.3f, 0.2f, 5.f}, {0.f, 0.f, -1.f}, hit));
    expectNear(hit.ns, {0.f, 0.f, 1.f}, 1e-7f);
    // Sheared along x by z: the disk's plane does not move, and neither does its normal (the inverse
    // transpose; to_world applied to +z as a vector would tilt it).
    const Traced sheared(load("disk_shear", "disk", "<transform name=\"to_world\"><matrix value=\"1 0 0.5 0 0 1 0 0 "
                                                    "0 0 1 0 0 0 0 1\"/></transform>\n"));
    ASSERT_TRUE(sheared.trace({0.3f, 0.2f, 5.f}, {0.f, 0.f, -1.f}, hit));
    expectNear(hit.ns, {0.f, 0.f, 1.f}, 1e-7f);
    // Rotated: the normal follows (about x by 90 degrees, +z turns to -y).
    const Traced turned(load("disk_turned", "disk", "<transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/>"
                                                    "</transform>\n"));
    ASSERT_TRUE(turned.trace({0.2f, -5.f, 0.3f}, {0.f, 1.f, 0.f}, hit));
    expectNear(hit.ns, {0.f, -1.f, 0.f}, 1e-6f);
    expectNear(hit.p, {0.2f, 0.f, 0.3f}, 1e-6f);
}

TEST(Disk, FarFromTheOriginTheHitLiesOnItsPlane) {
    // A tilted disk 1e4 away (as far as scene_limits.h lets a unit shape go).
    const Traced t(load("disk_far", "disk", "<transform name=\"to_world\"><rotate x=\"1\" angle=\"30\"/>"
                                            "<translate value=\"1e4, 0, 0\"/></transform>\n"));
    const Vec3d n(0.0, -0.5, std::sqrt(3.0) / 2.0);  // +z turned by 30 degrees about x
    for (int i = 0; i < 64; ++i) {
        const float a = 0.1f * float(i);
        Hit hit;
        ASSERT_TRUE(t.trace({1e4f + 0.5f * std::cos(a), 0.5f * std::sin(a), 7.f}, {0.0005f * i, 0.001f, -1.f}, hit)) << i;
        // The distance of the hit from the plane, from its float coordinates: within their rounding.
        const double off = dot(Vec3d(hit.p) - Vec3d(1e4, 0.0, 0.0), n);
        EXPECT_LT(std::abs(off), 1e-3) << i;  // half an ulp of 1e4 is 4.9e-4
    }
}

TEST(Disk, RefusesADegenerateOrUnboundedToWorld) {
    EXPECT_NE(errorOf("disk_zero", "disk", "<transform name=\"to_world\">\n<scale value=\"0, 1, 1\"/></transform>\n")
                  .find(":5: <scale>: transform matrix is singular"),
              std::string::npos);
    EXPECT_NE(errorOf("disk_flat", "disk", "<transform name=\"to_world\"><matrix value=\"1 1 0 0 0 1e-7 0 0 0 0 1 0 "
                                           "0 0 0 1\"/></transform>\n").find("the disk's to_world is degenerate"),
              std::string::npos);
    EXPECT_NE(errorOf("disk_far", "disk", "<transform name=\"to_world\"><translate value=\"2e15, 0, 0\"/>"
                                          "</transform>\n").find("must lie within"),
              std::string::npos);
    EXPECT_NE(errorOf("disk_speck", "disk", "<transform name=\"to_world\"><scale value=\"1e-3\"/>"
                                            "<translate value=\"1e6, 0, 0\"/></transform>\n")
                  .find("float32 could not place points on it"),
              std::string::npos);
    EXPECT_NE(errorOf("disk_radius", "disk", "<float name=\"radius\" value=\"2\"/>\n").find("unsupported property"),
              std::string::npos);
}

TEST(Cylinder, HitsItsSideFromOutsideAndInsideWithTheOutwardNormal) {
    const Traced t(load("cyl", "cylinder", ""));
    Hit hit;
    ASSERT_TRUE(t.trace({5.f, 0.f, 0.5f}, {-1.f, 0.f, 0.f}, hit));
    EXPECT_NEAR(hit.t, 4.f, 1e-6f);
    expectNear(hit.p, {1.f, 0.f, 0.5f}, 1e-6f);
    expectNear(hit.ns, {1.f, 0.f, 0.f}, 1e-7f);
    // From inside: the far wall, its normal still outward (Mitsuba's: one-sided shading sees the back).
    ASSERT_TRUE(t.trace({0.f, 0.f, 0.5f}, {1.f, 0.f, 0.f}, hit));
    EXPECT_NEAR(hit.t, 1.f, 1e-6f);
    expectNear(hit.ns, {1.f, 0.f, 0.f}, 1e-7f);
    // Open: a ray through the caps' plane inside the circle passes; beyond z = 1, along the axis, or beside it, none.
    EXPECT_FALSE(t.trace({0.2f, 0.f, 5.f}, {0.f, 0.f, -1.f}, hit));
    EXPECT_FALSE(t.trace({5.f, 0.f, 1.5f}, {-1.f, 0.f, 0.f}, hit));
    EXPECT_FALSE(t.trace({5.f, 1.2f, 0.5f}, {-1.f, 0.f, 0.f}, hit));
    // Through the open top, down onto the inside of the wall.
    ASSERT_TRUE(t.trace({0.f, 0.f, 2.f}, {1.f, 0.f, -1.f}, hit));
    expectNear(hit.p, {1.f, 0.f, 1.f}, 1e-6f);
}

TEST(Cylinder, P0P1AndRadiusComposeWithToWorldAsInMitsuba) {
    // Along x from 0 to 2, radius 0.5, then lifted by 1 in z: Mitsuba hits (1, 0.5, 1) from (1, 5, 1) at t = 4.5.
    const Traced t(load("cyl_p", "cylinder", "<point name=\"p0\" value=\"0, 0, 0\"/><point name=\"p1\" value=\"2, 0, 0\"/>"
                                             "<float name=\"radius\" value=\"0.5\"/><transform name=\"to_world\">"
                                             "<translate value=\"0, 0, 1\"/></transform>\n"));
    Hit hit;
    ASSERT_TRUE(t.trace({1.f, 5.f, 1.f}, {0.f, -1.f, 0.f}, hit));
    EXPECT_NEAR(hit.t, 4.5f, 1e-6f);
    expectNear(hit.p, {1.f, 0.5f, 1.f}, 1e-6f);
    expectNear(hit.ns, {0.f, 1.f, 0.f}, 1e-6f);
    EXPECT_FALSE(t.trace({2.5f, 5.f, 1.f}, {0.f, -1.f, 0.f}, hit));  // past p1
    EXPECT_FALSE(t.trace({-0.1f, 5.f, 1.f}, {0.f, -1.f, 0.f}, hit));  // before p0
    // A planted wrong radius (the default, 1) moves the hit.
    const Traced wrong(load("cyl_p_wrong", "cylinder", "<point name=\"p1\" value=\"2, 0, 0\"/><transform "
                                                       "name=\"to_world\"><translate value=\"0, 0, 1\"/></transform>\n"));
    ASSERT_TRUE(wrong.trace({1.f, 5.f, 1.f}, {0.f, -1.f, 0.f}, hit));
    EXPECT_NEAR(hit.t, 4.f, 1e-6f);
}

TEST(Cylinder, FlipNormalsPointsInwardAndAMirrorKeepsThemOutward) {
    Hit hit;
    ASSERT_TRUE(Traced(load("cyl_flip", "cylinder", "<boolean name=\"flip_normals\" value=\"true\"/>\n"))
                    .trace({5.f, 0.f, 0.5f}, {-1.f, 0.f, 0.f}, hit));
    expectNear(hit.ns, {-1.f, 0.f, 0.f}, 1e-7f);
    // Mitsuba: cross(dp/du, dp/dv) turns inward under a mirror, and its decomposition's negative scale
    // turns it back.
    ASSERT_TRUE(Traced(load("cyl_mirror", "cylinder", "<transform name=\"to_world\"><scale value=\"-1, 1, 1\"/>"
                                                      "</transform>\n"))
                    .trace({5.f, 0.f, 0.5f}, {-1.f, 0.f, 0.f}, hit));
    expectNear(hit.ns, {1.f, 0.f, 0.f}, 1e-7f);
    // Stretched along x (Mitsuba warns and keeps the elliptic cylinder): hit at x = 2.
    ASSERT_TRUE(Traced(load("cyl_stretch", "cylinder", "<transform name=\"to_world\"><scale value=\"2, 1, 1\"/>"
                                                       "</transform>\n"))
                    .trace({5.f, 0.f, 0.5f}, {-1.f, 0.f, 0.f}, hit));
    EXPECT_NEAR(hit.t, 3.f, 1e-6f);
    expectNear(hit.ns, {1.f, 0.f, 0.f}, 1e-7f);
}

TEST(Cylinder, FarFromTheOriginTheHitLiesOnItsSurface) {
    const Traced t(load("cyl_far", "cylinder", "<point name=\"p0\" value=\"1e4, 0, -1\"/>"
                                               "<point name=\"p1\" value=\"1e4, 0, 1\"/>\n"));
    for (int i = 0; i < 64; ++i) {
        const float a = 0.1f * float(i);
        Hit hit;
        ASSERT_TRUE(t.trace({1e4f + 5.f * std::cos(a), 5.f * std::sin(a), 0.f}, {-std::cos(a), -std::sin(a), 0.003f * i},
                            hit)) << i;
        const double r = std::hypot(double(hit.p.x) - 1e4, double(hit.p.y));
        EXPECT_LT(std::abs(r - 1.0), 1e-3) << i;  // half an ulp of 1e4 is 4.9e-4
        EXPECT_NEAR(hit.ns.x * std::cos(a) + hit.ns.y * std::sin(a), 1.f, 1e-4f) << i;  // outward, toward the ray
    }
}

TEST(Cylinder, RefusesABadRadiusAxisOrToWorld) {
    EXPECT_NE(errorOf("cyl_r0", "cylinder", "<float name=\"radius\" value=\"0\"/>\n").find(":4: <float>: radius must be "
                                                                                          "positive"),
              std::string::npos);
    EXPECT_NE(errorOf("cyl_axis", "cylinder", "<point name=\"p0\" value=\"1, 1, 1\"/>\n<point name=\"p1\" "
                                              "value=\"1, 1, 1\"/>\n").find(":5: <point>: p1 must differ from p0"),
              std::string::npos);
    EXPECT_NE(errorOf("cyl_zero", "cylinder", "<transform name=\"to_world\"><scale value=\"1, 1, 0\"/></transform>\n")
                  .find("transform matrix is singular"),
              std::string::npos);
    EXPECT_NE(errorOf("cyl_flat", "cylinder", "<transform name=\"to_world\"><matrix value=\"1 1 0 0 0 1e-7 0 0 0 0 1 "
                                              "0 0 0 0 1\"/></transform>\n").find("the cylinder's to_world is degenerate"),
              std::string::npos);
    EXPECT_NE(errorOf("cyl_far", "cylinder", "<point name=\"p1\" value=\"0, 0, 2e15\"/>\n").find("must lie within"),
              std::string::npos);
}

TEST(DiskAndCylinder, ASceneOfBothRendersFiniteWithEveryIntegrator) {
    const std::string body = "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"50\"/>"
                             "<transform name=\"to_world\"><lookat origin=\"3, 2, 4\" target=\"0, 0, 0.5\" up=\"0, 0, 1\"/>"
                             "</transform><film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer "
                             "name=\"height\" value=\"24\"/></film></sensor>\n<shape type=\"disk\"><transform "
                             "name=\"to_world\"><scale value=\"3\"/></transform></shape>\n<shape type=\"cylinder\">"
                             "<float name=\"radius\" value=\"0.5\"/></shape>\n<emitter type=\"point\"><point "
                             "name=\"position\" value=\"2, 3, 4\"/><rgb name=\"intensity\" value=\"20\"/></emitter>\n"
                             "</scene>\n";
    const SceneDescription scene = loadScene(writeScene("both", body));
    expectFiniteAndLitUnderEveryIntegrator(scene);
}
