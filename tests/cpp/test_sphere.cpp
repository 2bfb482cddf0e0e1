// The exact sphere: hits at the exact distance at every scale and far from the origin, unit
// normals, occluded() agreeing with intersect(), its loader's checks, and finite renders.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "bsdf_albedo.h"

#include "embree_scene.h"
#include "image_counts.h"
#include "error.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

struct Placement {
    float scale;   ///< the radius
    float offset;  ///< the centre's x
};

/// The exact distance from o along unit-z-ish d to the sphere, in long double from the float inputs.
long double exactT(const Sphere &s, const Vec3f &o, const Vec3f &d) {
    const long double ox = (long double)o.x - s.center.x, oy = (long double)o.y - s.center.y,
                      oz = (long double)o.z - s.center.z;
    const long double a = (long double)d.x * d.x + (long double)d.y * d.y + (long double)d.z * d.z;
    const long double b = 2 * (ox * d.x + oy * d.y + oz * d.z);
    const long double c = ox * ox + oy * oy + oz * oz - (long double)s.radius * s.radius;
    return (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

std::string writeScene(const std::string &name, const std::string &body) {
    const fs::path path = fs::temp_directory_path() / ("mcval_sphere_" + name + ".xml");
    std::ofstream(path) << body;
    return path.string();
}

const std::string kSensor =
    "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><transform name=\"to_world\"><lookat "
    "origin=\"0, 0, 5\" target=\"0, 0, 0\"/></transform><film type=\"hdrfilm\"><integer name=\"width\" "
    "value=\"24\"/><integer name=\"height\" value=\"24\"/></film></sensor>\n";

std::string sphereScene(const std::string &shapeBody) {
    return "<scene version=\"3.0.0\">\n" + kSensor + "<shape type=\"sphere\">\n" + shapeBody +
           "</shape>\n<emitter type=\"point\"><point name=\"position\" value=\"2, 3, 4\"/>"
           "<rgb name=\"intensity\" value=\"20\"/></emitter>\n</scene>\n";
}

}  // namespace

class SphereAtEveryScale : public ::testing::TestWithParam<Placement> {};

TEST_P(SphereAtEveryScale, HitsAtTheExactDistanceWithAUnitNormal) {
    const Placement at = GetParam();
    std::vector<Sphere> spheres(1);
    spheres[0].center = {at.offset, 0.f, 0.f};
    spheres[0].radius = at.scale;
    const std::vector<Mesh> meshes;
    const EmbreeScene embree(meshes, spheres);
    const float r = at.scale;
    // Straight at the centre, off-axis, and grazing near the silhouette.
    for (const Vec3f &aim : {Vec3f(0.f, 0.f, 0.f), Vec3f(0.3f, 0.2f, 0.f), Vec3f(0.f, 0.999f, 0.f)}) {
        Ray ray;
        ray.o = Vec3f(at.offset + aim.x * r, aim.y * r, 5.f * r);
        ray.d = normalize(Vec3f(0.f, 0.f, -1.f));
        const long double expected = exactT(spheres[0], ray.o, ray.d);
        Hit hit, hit8;
        ASSERT_TRUE(embree.intersect(ray, hit));
        bool found = false;
        embree.intersect16(&ray, 1, &hit8, &found);
        ASSERT_TRUE(found);
        EXPECT_NEAR(hit.t, expected, 1e-6 * expected) << r;
        EXPECT_EQ(hit.t, hit8.t);
        EXPECT_EQ(hit.geom, 0u);
        EXPECT_NEAR(norm(hit.ng), 1.f, 1e-6f);
        EXPECT_EQ(hit.ns.x, hit.ng.x);
        // On the sphere to float32's precision of its coordinates, the normal radial and outward.
        const Vec3f v = hit.p - spheres[0].center;
        const float ulp = std::nextafter(std::abs(at.offset) + r, 1e30f) - (std::abs(at.offset) + r);
        EXPECT_NEAR(norm(v), r, 2.f * ulp + 1e-6f * r);
        EXPECT_GT(dot(v, hit.ng), 0.999f * r);
        // occluded() agrees: blocked just past the hit, free just before it.
        Ray shadow = ray;
        shadow.tfar = float(expected * 1.0001L);
        EXPECT_TRUE(embree.occluded(shadow));
        shadow.tfar = float(expected * 0.9999L);
        EXPECT_FALSE(embree.occluded(shadow));
    }
    Ray miss;
    miss.o = Vec3f(at.offset + 1.01f * r, 0.f, 5.f * r);
    miss.d = Vec3f(0.f, 0.f, -1.f);
    Hit hit;
    EXPECT_FALSE(embree.intersect(miss, hit));
    EXPECT_FALSE(embree.occluded(miss));
}

INSTANTIATE_TEST_SUITE_P(Scales, SphereAtEveryScale,
                         ::testing::Values(Placement{1e-3f, 0.f}, Placement{1.f, 0.f}, Placement{1e3f, 0.f},
                                           Placement{1.f, 1e5f}, Placement{1e-3f, 1.f}),
                         [](const auto &info) { return "case" + std::to_string(info.index); });

TEST(Sphere, LoadsCenterRadiusToWorldAndFlip) {
    const SceneDescription scene = loadScene(writeScene(
        "props", sphereScene("<point name=\"center\" value=\"1, 0, 0\"/><float name=\"radius\" value=\"0.5\"/>"
                             "<boolean name=\"flip_normals\" value=\"true\"/><transform name=\"to_world\">"
                             "<scale value=\"2\"/><rotate z=\"1\" angle=\"90\"/><translate value=\"0, 0, 1\"/>"
                             "</transform><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.25\"/></bsdf>\n")));
    ASSERT_EQ(scene.spheres.size(), 1u);
    const Sphere &s = scene.spheres[0];
    EXPECT_NEAR(s.center.x, 0.f, 1e-6f);
    EXPECT_NEAR(s.center.y, 2.f, 1e-6f);
    EXPECT_NEAR(s.center.z, 1.f, 1e-6f);
    EXPECT_NEAR(s.radius, 1.f, 1e-6f);
    EXPECT_TRUE(s.flipNormals);
    EXPECT_FLOAT_EQ(test::frontAlbedo(scene, s).x, 0.25f);
    // A mirror flips the normals, as Mitsuba's sphere does.
    EXPECT_TRUE(loadScene(writeScene("mirror", sphereScene("<transform name=\"to_world\"><scale value=\"-1\"/>"
                                                           "</transform>\n")))
                    .spheres[0]
                    .flipNormals);
}

TEST(Sphere, FlippedNormalsPointInward) {
    std::vector<Sphere> spheres(1);
    spheres[0].flipNormals = true;
    const std::vector<Mesh> meshes;
    const EmbreeScene embree(meshes, spheres);
    Ray ray;
    ray.o = {0.f, 0.f, 0.f};
    ray.d = {0.f, 0.f, 1.f};
    Hit hit;
    ASSERT_TRUE(embree.intersect(ray, hit));
    EXPECT_FLOAT_EQ(hit.t, 1.f);
    EXPECT_FLOAT_EQ(hit.ng.z, -1.f);
}

TEST(Sphere, RefusesWhatMitsubaWouldNotKeepASphere) {
    const auto errorOf = [](const std::string &name, const std::string &body) -> std::string {
        try {
            loadScene(writeScene(name, sphereScene(body)));
        } catch (const SceneError &e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(errorOf("uneven", "<transform name=\"to_world\">\n<scale value=\"1, 2, 1\"/></transform>\n")
                  .find(":4: <transform>: a sphere's to_world may only translate, rotate and scale uniformly"),
              std::string::npos);
    EXPECT_NE(errorOf("shear", "<transform name=\"to_world\"><matrix value=\"1 0.5 0 0 0 1 0 0 0 0 1 0 0 0 0 1\"/>"
                               "</transform>\n").find("shears or scales unevenly"),
              std::string::npos);
    EXPECT_NE(errorOf("zero", "<float name=\"radius\" value=\"0\"/>\n").find(":4: <float>: radius must be positive"),
              std::string::npos);
    EXPECT_NE(errorOf("negative", "<float name=\"radius\" value=\"-1\"/>\n").find("radius must be positive, got -1"),
              std::string::npos);
    EXPECT_NE(errorOf("far", "<point name=\"center\" value=\"1e15, 0, 0\"/>\n").find("must lie within"),
              std::string::npos);
    EXPECT_NE(errorOf("speck", "<point name=\"center\" value=\"1e6, 0, 0\"/><float name=\"radius\" value=\"1e-3\"/>\n")
                  .find("float32 could not place points on it"),
              std::string::npos);
    EXPECT_NE(errorOf("faces", "<boolean name=\"face_normals\" value=\"true\"/>\n").find("unsupported property"),
              std::string::npos);
}

TEST(Sphere, ASphereOnlySceneRendersFinite) {
    const SceneDescription scene = loadScene(writeScene("render", sphereScene("")));
    expectFiniteAndLitUnderEveryIntegrator(scene);
}
