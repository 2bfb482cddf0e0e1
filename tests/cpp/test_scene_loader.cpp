// Bad scene files give one clear error each: file, line, element, what was expected.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bsdf_albedo.h"

#include "error.h"
#include "camera.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

const char *kHeader = "<scene version=\"3.0.0\">\n";

std::string writeScene(const std::string &name, const std::string &body) {
    const fs::path path = fs::temp_directory_path() / ("mcval_test_" + name + ".xml");
    std::ofstream(path) << body;
    return path.string();
}

std::string sensor(const std::string &inner = "") {
    return "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>" + inner +
           "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>"
           "</film></sensor>\n";
}

const std::string kShape = "  <shape type=\"rectangle\"/>\n";

/// The SceneError message of loading body, or "" if it loads.
std::string errorOf(const std::string &name, const std::string &body) {
    const std::string path = writeScene(name, body);
    try {
        loadScene(path);
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneLoader, AValidSceneLoads) {
    const std::string path = writeScene("valid", std::string(kHeader) + "<default name=\"w\" value=\"0.3\"/>\n" +
                                                     sensor() + "  <shape type=\"cube\"><bsdf type=\"diffuse\">"
                                                     "<rgb name=\"reflectance\" value=\"$w, 0.2, 0.1\"/></bsdf></shape>\n"
                                                     "  <emitter type=\"point\"><point name=\"position\" value=\"0, 4, 0\"/>"
                                                     "</emitter>\n<integrator type=\"ao\"><integer name=\"samples\" "
                                                     "value=\"4\"/></integrator>\n</scene>\n");
    const SceneDescription scene = loadScene(path);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].indices.size(), 36u);
    EXPECT_FLOAT_EQ(test::frontAlbedo(scene, scene.meshes[0]).x, 0.3f);
    EXPECT_EQ(scene.integrator.type, "ao");
    EXPECT_TRUE(static_cast<bool>(scene.integrator.make));  // ao parsed its samples itself
    EXPECT_EQ(scene.film.width, 8);
    const SceneDescription overridden = loadScene(path, {{"w", "0.9"}});
    EXPECT_FLOAT_EQ(test::frontAlbedo(overridden, overridden.meshes[0]).x, 0.9f);
}

struct BadCase {
    const char *name;
    std::string body;
    const char *expected;  ///< a fragment of the message
    int line;
};

/// gtest prints the case by name.
void PrintTo(const BadCase &c, std::ostream *os) { *os << c.name; }

class SceneLoaderErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(SceneLoaderErrors, NamesFileLineAndWhatWasExpected) {
    const BadCase &c = GetParam();
    const std::string message = errorOf(c.name, c.body);
    ASSERT_FALSE(message.empty()) << c.name << " loaded without error";
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_NE(message.find("mcval_test_" + std::string(c.name) + ".xml:" + std::to_string(c.line) + ":"),
              std::string::npos)
        << message;
}

INSTANTIATE_TEST_SUITE_P(
    Kinds, SceneLoaderErrors,
    ::testing::Values(
        BadCase{"malformed", std::string(kHeader) + sensor() + "<shape type=\"cube\">\n</scene>\n", "malformed XML", 4},
        BadCase{"normalmap", std::string(kHeader) + sensor() +
                "  <shape type=\"rectangle\">\n    <bsdf type=\"normalmap\"/></shape>\n</scene>\n",
                "perturbs the shading normal", 4},
        BadCase{"unknown_element", std::string(kHeader) + sensor() + "  <light type=\"spot\"/>\n</scene>\n",
                "unsupported element", 3},
        BadCase{"nori_dialect", std::string(kHeader) + "  <camera type=\"perspective\"/>\n</scene>\n",
                "this is Nori's scene dialect, not Mitsuba 3's: the harness translates it", 2},
        BadCase{"unknown_shape", std::string(kHeader) + sensor() + "  <shape type=\"hair\"/>\n</scene>\n",
                "(every integrator sees it, so it cannot be left out): expected obj, ply, serialized, rectangle, "
                "cube, sphere, disk or cylinder", 3},
        BadCase{"unknown_property", std::string(kHeader) + sensor() +
                "  <shape type=\"cube\">\n    <boolean name=\"flip_normals\" value=\"true\"/>\n  </shape>\n</scene>\n",
                "unsupported property \"flip_normals\"", 4},
        BadCase{"bad_number", std::string(kHeader) + sensor() + kShape +
                "  <emitter type=\"point\">\n    <rgb name=\"intensity\" value=\"1, x, 1\"/>\n  </emitter>\n</scene>\n",
                "expected a number, got \"x\"", 5},
        BadCase{"fov_axis_without_fov", std::string(kHeader) +
                "  <sensor type=\"perspective\">\n    <string name=\"fov_axis\" value=\"y\"/></sensor>\n" + kShape +
                "</scene>\n", "fov_axis goes with fov", 3},
        BadCase{"undefined_parameter", std::string(kHeader) + sensor() +
                "  <integrator type=\"$integrator\"/>\n" + kShape + "</scene>\n", "parameter $integrator", 3},
        BadCase{"missing_mesh", std::string(kHeader) + sensor() +
                "  <shape type=\"ply\"><string name=\"filename\" value=\"nowhere.ply\"/></shape>\n</scene>\n",
                "nowhere.ply", 3},
        BadCase{"bad_integrator", std::string(kHeader) + sensor() + kShape + "  <integrator type=\"bdpt\"/>\n</scene>\n",
                // The start of the sorted list of choices (test_integrator_registry.cpp checks it whole).
                "unsupported integrator type \"bdpt\": expected albedo, ao, ao_uniform, ", 4},
        BadCase{"bad_rfilter", std::string(kHeader) +
                "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n    <film type=\"hdrfilm\">\n"
                "      <rfilter type=\"lanczos\"/></film></sensor>\n" + kShape + "</scene>\n",
                "expected box, gaussian or tent", 4},
        BadCase{"unknown_ref", std::string(kHeader) + sensor() + "  <shape type=\"cube\">\n    <ref id=\"gold\"/>\n"
                "  </shape>\n</scene>\n", "no <bsdf id=\"gold\">", 4},
        // Numbers: finite, in range, with bounded work; the error points at the property's line.
        BadCase{"nan_reflectance", std::string(kHeader) + sensor() + "  <shape type=\"cube\"><bsdf type=\"diffuse\">\n"
                "    <rgb name=\"reflectance\" value=\"nan\"/></bsdf></shape>\n</scene>\n",
                "expected a finite number, got \"nan\"", 4},
        BadCase{"negative_reflectance", std::string(kHeader) + sensor() + "  <shape type=\"cube\"><bsdf type=\"diffuse\">\n"
                "    <float name=\"reflectance\" value=\"-0.5\"/></bsdf></shape>\n</scene>\n",
                "reflectance must lie in [0, 1], got -0.5", 4},
        BadCase{"infinite_light", std::string(kHeader) + sensor() + kShape +
                "  <emitter type=\"point\">\n    <point name=\"position\" value=\"Infinity, 0, 0\"/></emitter>\n</scene>\n",
                "expected a finite number, got \"Infinity\"", 5},
        BadCase{"far_light", std::string(kHeader) + sensor() + kShape +
                "  <emitter type=\"point\">\n    <point name=\"position\" value=\"1e20, 0, 0\"/></emitter>\n</scene>\n",
                "position must lie in", 5},
        BadCase{"negative_intensity", std::string(kHeader) + sensor() + kShape +
                "  <emitter type=\"point\">\n    <rgb name=\"intensity\" value=\"1, -1, 1\"/></emitter>\n</scene>\n",
                "intensity must lie in", 5},
        BadCase{"overflowing_float", std::string(kHeader) + sensor() + kShape +
                "  <emitter type=\"constant\">\n    <rgb name=\"radiance\" value=\"1e39\"/></emitter>\n</scene>\n",
                "expected a finite number, got \"1e39\"", 5},
        BadCase{"singular_scale", std::string(kHeader) + sensor() + "  <shape type=\"cube\"><transform name=\"to_world\">\n"
                "    <scale value=\"0\"/></transform></shape>\n</scene>\n", "transform matrix is singular", 4},
        BadCase{"overflowing_transform", std::string(kHeader) + sensor() + "  <shape type=\"cube\"><transform "
                "name=\"to_world\"><scale value=\"1e30\"/>\n    <scale value=\"1e30\"/></transform></shape>\n</scene>\n",
                "not finite", 4},
        BadCase{"far_vertices", std::string(kHeader) + sensor() + "  <shape type=\"cube\">\n    <transform "
                "name=\"to_world\"><scale value=\"1e16\"/></transform></shape>\n</scene>\n",
                "coordinates must be finite and within", 3},
        // Mitsuba 3 does not normalise a rotate axis: (0.3, 1, 0.2) would be a shear there, a rotation here.
        BadCase{"non_unit_rotate_axis", std::string(kHeader) + sensor() + "  <shape type=\"cube\"><transform "
                "name=\"to_world\">\n    <rotate x=\"0.3\" y=\"1\" z=\"0.2\" angle=\"37\"/></transform></shape>\n"
                "</scene>\n", "rotate axis (0.3, 1, 0.2) has length 1.063, not 1: Mitsuba 3 would shear", 4},
        BadCase{"long_rotate_axis", std::string(kHeader) + sensor() + "  <shape type=\"cube\"><transform "
                "name=\"to_world\">\n    <rotate value=\"0, 2, 0\" angle=\"37\"/></transform></shape>\n</scene>\n",
                "has length 2, not 1", 4},
        BadCase{"zero_up", std::string(kHeader) + sensor("<transform name=\"to_world\">\n<lookat origin=\"0, 0, 5\" "
                "target=\"0, 0, 0\" up=\"0, 0, 0\"/></transform>") + kShape + "</scene>\n", "up is zero or parallel", 3},
        BadCase{"huge_filter", std::string(kHeader) + "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
                "    <film type=\"hdrfilm\"><rfilter type=\"gaussian\">\n      <float name=\"stddev\" value=\"1e6\"/>"
                "</rfilter></film></sensor>\n" + kShape + "</scene>\n", "stddev must lie in [0.05, 4]", 4},
        BadCase{"endless_ao", std::string(kHeader) + sensor() + kShape + "  <integrator type=\"ao\">\n    <integer "
                "name=\"samples\" value=\"2147483647\"/></integrator>\n</scene>\n", "samples must be in 1..1024", 5},
        BadCase{"huge_sample_count", std::string(kHeader) + "  <sensor type=\"perspective\"><float name=\"fov\" "
                "value=\"40\"/>\n    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"2000000000\"/>"
                "</sampler></sensor>\n" + kShape + "</scene>\n", "sample_count must be in 1..", 3},
        BadCase{"huge_film", std::string(kHeader) + "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>\n"
                "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"16385\"/></film></sensor>\n" + kShape +
                "</scene>\n", "width must be in 1..16384", 3},
        BadCase{"zero_fov", std::string(kHeader) + "  <sensor type=\"perspective\">\n    <float name=\"fov\" value=\"0\"/>"
                "</sensor>\n" + kShape + "</scene>\n", "fov must lie in", 3}),
    [](const auto &info) { return std::string(info.param.name); });

TEST(SceneLoader, AUnitRotateAxisLoadsWithinFloatRounding) {
    // 0.6, 0.8 is exactly unit; 0.57735 three times is unit to 1e-5 (as a file would round 1/sqrt(3)).
    for (const char *axis : {"x=\"0.6\" y=\"0.8\"", "x=\"0.57735\" y=\"0.57735\" z=\"0.57735\""}) {
        const std::string body = std::string(kHeader) + sensor() + "  <shape type=\"cube\"><transform name=\"to_world\">"
                                 "<rotate " + axis + " angle=\"30\"/></transform></shape>\n</scene>\n";
        EXPECT_EQ(errorOf("unit_axis", body), "") << axis;
    }
}

TEST(SceneLoader, EveryShippedSceneLoads) {
    for (const auto &entry : fs::directory_iterator(fs::path(MCVAL_SOURCE_DIR) / "scenes")) {
        if (entry.path().extension() != ".xml" || entry.path().filename().string()[0] == '.') continue;
        EXPECT_NO_THROW(loadScene(entry.path().string())) << entry.path();
    }
}

// Issue 11: what the chosen integrator needs is modelled, what it ignores is skipped, what would change
// its answer is refused with file and line.
TEST(SceneLoader, TheCallersIntegratorOverridesTheFilesWhateverItsType) {
    const std::string path = writeScene(
        "override", std::string(kHeader) + sensor("<float name=\"focus_distance\" value=\"2\"/>") + kShape +
                        "  <integrator type=\"bdpt\"><integer name=\"max_depth\" value=\"8\"/></integrator>\n</scene>\n");
    EXPECT_NO_THROW(loadScene(path, {}, "ao"));
    EXPECT_NO_THROW(loadScene(path, {}, "normals"));
    try {
        loadScene(path);
        FAIL() << "an unknown file integrator without override must be an error";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find(":4:"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("\"bdpt\""), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, ComponentFormatIsHonouredOrRefused) {
    auto film = [](const std::string &fmt) {
        return std::string(kHeader) +
               "  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><film type=\"hdrfilm\">"
               "<string name=\"component_format\" value=\"" + fmt + "\"/><string name=\"pixel_format\" value=\"rgb\"/>"
               "</film></sensor>\n" + kShape + "</scene>\n";
    };
    EXPECT_EQ(loadScene(writeScene("half", film("float16")), {}, "normals").film.componentFormat, "float16");
    EXPECT_EQ(loadScene(writeScene("single", film("float32")), {}, "normals").film.componentFormat, "float32");
    const std::string path = writeScene("uint8", film("uint8"));
    try {
        loadScene(path, {}, "normals");
        FAIL() << "uint8 must be refused";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find(path + ":2:"), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, UnusedElementsAreSkippedAndAnswerChangingOnesRefused) {
    const std::string path = writeScene(
        "area_principled", std::string(kHeader) + sensor() +
                              "  <shape type=\"rectangle\"><bsdf type=\"principled\"/>"
                              "<emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n"
                              "  <emitter type=\"point\"/>\n</scene>\n");
    EXPECT_NO_THROW(loadScene(path, {}, "normals"));
    EXPECT_NO_THROW(loadScene(path, {}, "ao"));  // it reads no material, and no area emitter
    for (const char *integrator : {"simple", "direct"}) {
        try {
            loadScene(path, {}, integrator);
            FAIL() << integrator;
        } catch (const SceneError &e) {
            EXPECT_NE(std::string(e.what()).find(path + ":3:"), std::string::npos) << e.what();
        }
    }
}

TEST(SceneLoader, EmittersNoIntegratorUsesAreSkippedAndAPointLightTakesToWorld) {
    const std::string path = writeScene(
        "other_emitters",
        std::string(kHeader) + sensor() + kShape +
            "  <emitter type=\"point\"><transform name=\"to_world\"><translate x=\"1\" y=\"2\" z=\"3\"/></transform>"
            "</emitter>\n  <emitter type=\"spot\"><float name=\"cutoff_angle\" value=\"20\"/></emitter>\n"
            "  <emitter type=\"directional\"/>\n  <emitter type=\"projector\"/>\n"
            "  <emitter type=\"envmap\"><string name=\"filename\" value=\"nowhere.exr\"/></emitter>\n</scene>\n");
    for (const char *integrator : {"simple", "ao", "normals"}) {
        const SceneDescription scene = loadScene(path, {}, integrator);
        ASSERT_EQ(scene.pointLights.size(), 1u) << integrator;
        EXPECT_EQ(scene.pointLights[0].position.x, 1.f);
        EXPECT_EQ(scene.pointLights[0].position.y, 2.f);
        EXPECT_EQ(scene.pointLights[0].position.z, 3.f);
        EXPECT_FALSE(scene.environment.has_value());
    }
    const std::string both = std::string(kHeader) + sensor() + kShape +
                             "  <emitter type=\"point\"><point name=\"position\" value=\"0, 1, 0\"/>\n"
                             "    <transform name=\"to_world\"><translate x=\"1\"/></transform></emitter>\n</scene>\n";
    EXPECT_NE(errorOf("point_both", both).find("position or to_world, not both"), std::string::npos);
    EXPECT_NE(errorOf("unknown_emitter", std::string(kHeader) + sensor() + kShape +
                                             "  <emitter type=\"sunsky\"/>\n</scene>\n")
                  .find("unsupported emitter type \"sunsky\""),
              std::string::npos);
}

TEST(SceneLoader, ASensorWithoutFovHasMitsubasFocalLength) {
    // x_fov as Mitsuba 3.9 reports it (mi.traverse(sensor)["x_fov"]) on a 64 x 32 and a 32 x 64 film.
    auto xFov = [](const std::string &property, int width, int height) {
        const std::string body = std::string(kHeader) + "  <sensor type=\"perspective\">" + property +
                                 "<film type=\"hdrfilm\"><integer name=\"width\" value=\"" + std::to_string(width) +
                                 "\"/><integer name=\"height\" value=\"" + std::to_string(height) +
                                 "\"/></film></sensor>\n" + kShape + "</scene>\n";
        const SceneDescription scene = loadScene(writeScene("focal", body), {}, "normals");
        return Camera(scene.camera, width, height).fovX();
    };
    EXPECT_NEAR(xFov("", 64, 32), 42.311714f, 1e-3f);
    EXPECT_NEAR(xFov("", 32, 64), 21.902138f, 1e-3f);
    EXPECT_NEAR(xFov("<string name=\"focal_length\" value=\"35mm\"/>", 64, 32), 57.871193f, 1e-3f);
    EXPECT_NEAR(xFov("<string name=\"focal_length\" value=\"20\"/>", 64, 32), 88.105583f, 1e-3f);
    EXPECT_NE(errorOf("focal_bad", std::string(kHeader) +
                                       "  <sensor type=\"perspective\"><string name=\"focal_length\" value=\"wide\"/>"
                                       "</sensor>\n" + kShape + "</scene>\n")
                  .find("expected a focal length in millimetres"),
              std::string::npos);
}

TEST(SceneLoader, ASpectrumIsReadWhenConstantAndAnUnreadableReflectanceIsRefusedOnlyWhereItIsRead) {
    // (A spectrum given per wavelength is read too: test_spectrum_rgb.cpp.)
    // ao reads no material: only simple, direct and path refuse a reflectance they cannot read (a bitmap or a
    // checkerboard is read by direct and path: test_textures.cpp).
    const std::string constant = std::string(kHeader) + sensor() +
                                 "  <shape type=\"rectangle\"><bsdf type=\"diffuse\">"
                                 "<spectrum name=\"reflectance\" value=\"0.25\"/></bsdf></shape>\n</scene>\n";
    const SceneDescription scene = loadScene(writeScene("spectrum_constant", constant), {}, "ao");
    EXPECT_EQ(test::frontAlbedo(scene, scene.meshes.at(0)).x, 0.25f);
    EXPECT_EQ(test::frontAlbedo(scene, scene.meshes.at(0)).z, 0.25f);
    for (const std::string &reflectance :
         {std::string("<spectrum name=\"reflectance\" filename=\"paint.spd\"/>"),
          std::string("<texture type=\"mesh_attribute\" name=\"reflectance\"><string name=\"name\" "
                      "value=\"vertex_color\"/></texture>")}) {
        const std::string body = std::string(kHeader) + sensor() + "  <texture type=\"checkerboard\" id=\"c\"/>\n" +
                                 "  <shape type=\"rectangle\">\n    <bsdf type=\"diffuse\">" + reflectance +
                                 "</bsdf></shape>\n</scene>\n";
        const std::string path = writeScene("spectrum_unread", body);
        EXPECT_NO_THROW(loadScene(path, {}, "normals")) << reflectance;
        EXPECT_NO_THROW(loadScene(path, {}, "ao")) << reflectance;
        try {
            loadScene(path, {}, "direct");
            FAIL() << "direct reads the reflectance: " << reflectance;
        } catch (const SceneError &e) {
            EXPECT_NE(std::string(e.what()).find(":5:"), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("the direct integrator reads the reflectance"), std::string::npos)
                << e.what();
        }
    }
}

TEST(SceneLoader, AnEmittingShapeWithoutABsdfIsBlackAsMitsubasWhereItsEmitterIsRead) {
    // Mitsuba gives a shape with an area emitter and no BSDF a diffuse BSDF of reflectance 0; where the
    // integrator skips the emitter (ao, and Mitsuba's copy drops it), the shape is an ordinary one, 0.5.
    const std::string path = writeScene(
        "emitting_shape", std::string(kHeader) + sensor() +
                              "  <shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" "
                              "value=\"1\"/></emitter></shape>\n  <shape type=\"disk\"><emitter type=\"area\">"
                              "<rgb name=\"radiance\" value=\"1\"/></emitter><bsdf type=\"diffuse\"><rgb "
                              "name=\"reflectance\" value=\"0.3\"/></bsdf></shape>\n</scene>\n");
    const auto albedo = [](const SceneDescription &scene, uint32_t index) {
        return scene.bsdfs.at(index)->lambertianAlbedo(true).value().x;
    };
    for (const char *integrator : {"direct", "path"}) {
        const SceneDescription scene = loadScene(path, {}, integrator);
        EXPECT_EQ(albedo(scene, scene.meshes.at(0).bsdf), 0.f) << integrator;
        EXPECT_FLOAT_EQ(albedo(scene, scene.disks.at(0).bsdf), 0.3f) << integrator;
    }
    const SceneDescription ao = loadScene(path, {}, "ao");
    EXPECT_FLOAT_EQ(albedo(ao, ao.meshes.at(0).bsdf), 0.5f);
}
