// The orthographic sensor follows Mitsuba 3's orthographic_projection: the film's width spans x in
// [1, -1] (left to right, as the perspective camera's +x is the image's left), its height y in
// [1/aspect, -1/aspect], rays parallel to to_world's +z from the near plane over far_clip - near_clip;
// to_world may scale (it sizes the view). Its loader's checks, and what a render through it covers.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "camera.h"
#include "error.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

CameraSpec orthographic(const Transform &toWorld) {
    CameraSpec spec;
    spec.projection = CameraSpec::Projection::Orthographic;
    spec.toWorld = toWorld;
    return spec;
}

void expectNear(const Vec3f &a, const Vec3f &b, float tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

std::string writeScene(const std::string &name, const std::string &body) {
    const fs::path path = fs::temp_directory_path() / ("mcval_orthographic_" + name + ".xml");
    std::ofstream(path) << body;
    return path.string();
}

/// A 0.5 x 0.5 square at the origin facing +z, seen along -z by `sensor` on a width x height film.
std::string squareScene(const std::string &sensor, const std::string &sensorBody, int width, int height) {
    return "<scene version=\"3.0.0\">\n<sensor type=\"" + sensor + "\">\n" + sensorBody +
           "<film type=\"hdrfilm\"><integer name=\"width\" value=\"" + std::to_string(width) +
           "\"/><integer name=\"height\" value=\"" + std::to_string(height) +
           "\"/><rfilter type=\"box\"/></film></sensor>\n<shape type=\"rectangle\"><transform name=\"to_world\">"
           "<scale value=\"0.25\"/></transform></shape>\n</scene>\n";
}

const std::string kLookDown =
    "<transform name=\"to_world\"><lookat origin=\"0, 0, 5\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n";

/// The fraction of the film's pixels that see the square under `normals` (their z is not 0).
double coverage(const SceneDescription &scene) {
    RenderOptions options;
    options.spp = 4;
    options.integrator = "normals";
    const RenderOutput out = render(scene, options);
    size_t hit = 0;
    for (size_t i = 2; i < out.mean.rgb.size(); i += 3) hit += out.mean.rgb[i] != 0.f;
    return double(hit) / double(out.mean.rgb.size() / 3);
}

}  // namespace

TEST(Orthographic, TheFilmsWidthSpansTwoUnitsAndItsHeightFollowsTheAspect) {
    const Camera cam(orthographic(Transform()), 64, 32);
    const Ray corner = cam.generateRay(0.f, 0.f);
    expectNear(corner.o, {1.f, 0.5f, 1e-2f}, 1e-6f);  // the top-left corner: +x, +y, on the near plane
    expectNear(corner.d, {0.f, 0.f, 1.f}, 0.f);
    expectNear(cam.generateRay(64.f, 32.f).o, {-1.f, -0.5f, 1e-2f}, 1e-6f);
    expectNear(cam.generateRay(32.f, 16.f).o, {0.f, 0.f, 1e-2f}, 1e-6f);
    EXPECT_EQ(corner.tnear, 0.f);
    EXPECT_FLOAT_EQ(corner.tfar, 1e4f - 1e-2f);  // Mitsuba's maxt: far_clip - near_clip
    // Every ray is parallel.
    expectNear(cam.generateRay(5.f, 27.f).d, corner.d, 0.f);
}

TEST(Orthographic, ToWorldScalesTheViewAndPlacesItOnTheNearPlane) {
    CameraSpec spec = orthographic(Transform::lookAt({0, 0, 5}, {0, 0, 0}, {0, 1, 0}) * Transform::scale({10, 10, 2}));
    spec.nearClip = 0.5f;
    const Camera cam(spec, 32, 32);
    // to_world * (x, y, near): the scale's z moves the near plane too (Mitsuba maps the point, not a distance).
    const Ray left = cam.generateRay(0.f, 16.f);
    expectNear(left.o, {-10.f, 0.f, 4.f}, 1e-5f);  // the image's left edge is the viewer's left (-x here)
    expectNear(left.d, {0.f, 0.f, -1.f}, 1e-6f);
    expectNear(cam.generateRay(16.f, 0.f).o, {0.f, 10.f, 4.f}, 1e-5f);  // the top is up
}

TEST(Orthographic, ARenderCoversTheAreaItsViewSpans) {
    // The square is 0.5 x 0.5: a quarter of 1 x 1, a sixteenth of the unit view [-1, 1]^2, and a
    // sixty-fourth of the view scaled by 2.
    const auto load = [](const std::string &name, const std::string &body, int w, int h) {
        return loadScene(writeScene(name, squareScene("orthographic", body, w, h)));
    };
    EXPECT_NEAR(coverage(load("unit", kLookDown, 32, 32)), 1.0 / 16.0, 1e-9);
    EXPECT_NEAR(coverage(load("scaled", "<transform name=\"to_world\"><scale value=\"2\"/><lookat origin=\"0, 0, 5\" "
                                        "target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n", 32, 32)),
                1.0 / 64.0, 1e-9);
    // A 64 x 32 film sees [-1, 1] x [-0.5, 0.5]: the square is 1/8 of it. A planted wrong aspect (the height
    // spanning two units too) would give 1/16.
    EXPECT_NEAR(coverage(load("wide", kLookDown, 64, 32)), 1.0 / 8.0, 1e-9);
    // The same file with a perspective sensor covers something else.
    const SceneDescription perspective =
        loadScene(writeScene("persp", squareScene("perspective", "<float name=\"fov\" value=\"40\"/>" + kLookDown, 32, 32)));
    EXPECT_GT(std::abs(coverage(perspective) - 1.0 / 16.0), 0.01);
}

TEST(Orthographic, TheLoaderReadsItsPropertiesAndRefusesTheRest) {
    const SceneDescription scene = loadScene(writeScene(
        "props", squareScene("orthographic", "<float name=\"near_clip\" value=\"0.5\"/><float name=\"far_clip\" "
                                             "value=\"20\"/>" + kLookDown, 16, 16)));
    EXPECT_EQ(scene.camera.projection, CameraSpec::Projection::Orthographic);
    EXPECT_FLOAT_EQ(scene.camera.nearClip, 0.5f);
    EXPECT_FLOAT_EQ(scene.camera.farClip, 20.f);
    const auto errorOf = [](const std::string &name, const std::string &sensor, const std::string &body) -> std::string {
        try {
            loadScene(writeScene(name, squareScene(sensor, body, 16, 16)));
        } catch (const SceneError &e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(errorOf("fov", "orthographic", "<float name=\"fov\" value=\"40\"/>\n").find(":3: <float>: unsupported "
                                                                                         "property \"fov\""),
              std::string::npos);
    EXPECT_NE(errorOf("zero", "orthographic", "<transform name=\"to_world\">\n<scale value=\"0, 1, 1\"/></transform>\n")
                  .find(":4: <scale>: transform matrix is singular"),
              std::string::npos);
    EXPECT_NE(errorOf("flat", "orthographic", "<transform name=\"to_world\"><matrix value=\"1 1 0 0 0 1e-7 0 0 0 0 1 0 "
                                              "0 0 0 1\"/></transform>\n").find(":2: <sensor>: the orthographic camera's "
                                                                               "to_world is degenerate"),
              std::string::npos);
    EXPECT_NE(errorOf("huge", "orthographic", "<transform name=\"to_world\"><scale value=\"1e16\"/></transform>\n")
                  .find("a corner of the orthographic camera's view"),
              std::string::npos);
    EXPECT_NE(errorOf("clip", "orthographic", "<float name=\"near_clip\" value=\"2\"/><float name=\"far_clip\" "
                                              "value=\"1\"/>\n").find("need 0 < near_clip < far_clip"),
              std::string::npos);
    // A scaled perspective camera stays refused: only the orthographic one may scale.
    EXPECT_NE(errorOf("pscale", "perspective", "<float name=\"fov\" value=\"40\"/><transform name=\"to_world\">"
                                               "<scale value=\"2\"/></transform>\n").find("scales or shears"),
              std::string::npos);
    EXPECT_NE(errorOf("other", "thinlens", "").find("expected \"perspective\" or \"orthographic\""), std::string::npos);
}
