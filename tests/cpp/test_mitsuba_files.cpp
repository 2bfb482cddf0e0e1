// Scene files as Mitsuba 3 reads them: what it loads and our integrators' answers do not depend on loads here
// too (sampler kinds, converted property types, forward references, the 0.5 upgrade, media, unused emitters);
// what changes the image (twosided, the tent filter, crop windows) is modelled; the rest fails with its line.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bsdf_albedo.h"

#include "camera.h"
#include "error.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

std::string writeScene(const std::string &name, const std::string &body) {
    const fs::path path = fs::temp_directory_path() / ("mcval_mitsuba_" + name + ".xml");
    std::ofstream(path) << body;
    return path.string();
}

/// A 3.0.0 scene: a perspective camera looking down -z at `shapes`, with `sensorInner` in the sensor.
std::string scene(const std::string &shapes, const std::string &sensorInner = "", const std::string &version = "3.0.0") {
    return "<scene version=\"" + version + "\">\n  <sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>" +
           sensorInner + "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" "
           "value=\"8\"/></film></sensor>\n" + shapes + "</scene>\n";
}

/// The SceneError message of loading `body` under `integrator`, or "" if it loads.
std::string errorOf(const std::string &name, const std::string &body, const std::string &integrator = "normals") {
    try {
        loadScene(writeScene(name, body), {}, integrator);
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

const std::string kRectangle = "  <shape type=\"rectangle\"/>\n";

}  // namespace

TEST(MitsubaFiles, EveryMitsubaSamplerKindAndItsSeedLoad) {
    for (const char *kind : {"independent", "stratified", "multijitter", "orthogonal", "ldsampler", "sobol"}) {
        const std::string body = scene(kRectangle, std::string("<sampler type=\"") + kind + "\"><integer name=\"seed\" "
                                       "value=\"9\"/><integer name=\"sample_count\" value=\"16\"/></sampler>");
        const SceneDescription s = loadScene(writeScene("sampler", body), {}, "normals");
        EXPECT_EQ(s.sampleCount, 16) << kind;
        EXPECT_EQ(s.sampler, std::string(kind) == "independent" ? SamplerType::Independent : SamplerType::Sobol) << kind;
    }
    // A kind's own knobs on that kind only, as Mitsuba reads them (it fails on a property nothing reads).
    EXPECT_EQ(errorOf("jitter", scene(kRectangle, "<sampler type=\"orthogonal\"><boolean name=\"jitter\" "
                                                  "value=\"false\"/><integer name=\"strength\" value=\"2\"/></sampler>")),
              "");
    EXPECT_TRUE(contains(errorOf("jitter", scene(kRectangle, "<sampler type=\"independent\"><boolean name=\"jitter\" "
                                                             "value=\"false\"/></sampler>")),
                         "unsupported property \"jitter\""));
    const std::string message = errorOf("halton", scene(kRectangle, "\n<sampler type=\"halton\"/>"));
    EXPECT_TRUE(contains(message, "mcval_mitsuba_halton.xml:3:")) << message;
    EXPECT_TRUE(contains(message, "expected independent, stratified, multijitter, orthogonal, ldsampler")) << message;
}

TEST(MitsubaFiles, PropertyTypesMitsubaConvertsAreRead) {
    // An <integer> where a float is read (fov, a reflectance), a <vector> for a <point>, "True" for true.
    const std::string body =
        "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"><integer name=\"fov\" value=\"45\"/></sensor>\n"
        "  <shape type=\"rectangle\"><bsdf type=\"diffuse\"><integer name=\"reflectance\" value=\"1\"/></bsdf></shape>\n"
        "  <emitter type=\"point\"><vector name=\"position\" value=\"1, 2, 3\"/></emitter>\n"
        "  <integrator type=\"ao\"><boolean name=\"hide_emitters\" value=\"False\"/></integrator>\n</scene>\n";
    const SceneDescription s = loadScene(writeScene("conversions", body));
    EXPECT_EQ(s.camera.fov, 45.f);
    EXPECT_EQ(test::frontAlbedo(s, s.meshes.at(0)).y, 1.f);
    EXPECT_EQ(s.pointLights.at(0).position.z, 3.f);
    EXPECT_EQ(s.hideEmitters, std::optional<bool>(false));
    // What Mitsuba does not convert stays an error: a float where an integer is read.
    EXPECT_TRUE(contains(errorOf("float_for_int", scene(kRectangle, "<sampler type=\"independent\"><float "
                                                             "name=\"sample_count\" value=\"4\"/></sampler>")),
                         "must be a <integer>"));
}

TEST(MitsubaFiles, APrincipalPointOffsetMovesTheViewAsMitsubas) {
    // Mitsuba's perspective: film position (x, y) looks where (x + ox width, y + oy height) would without it.
    const auto camera = [](const std::string &offsets) {
        const SceneDescription s = loadScene(writeScene("principal", scene(kRectangle, offsets)), {}, "normals");
        return Camera(s.camera, 8, 8);
    };
    const Camera plain = camera(""), moved = camera("<float name=\"principal_point_offset_x\" value=\"0.25\"/>"
                                                    "<integer name=\"principal_point_offset_y\" value=\"-1\"/>");
    for (const float x : {0.f, 3.5f, 8.f}) {
        float length;
        const Vec3f got = moved.direction(x, 2.f, length), expected = plain.direction(x + 2.f, 2.f - 8.f, length);
        EXPECT_NEAR(got.x, expected.x, 1e-6f);
        EXPECT_NEAR(got.y, expected.y, 1e-6f);
        EXPECT_NEAR(got.z, expected.z, 1e-6f);
        EXPECT_GT(std::abs(got.x - plain.direction(x, 2.f, length).x) + std::abs(got.y - plain.direction(x, 2.f, length).y),
                  1e-2f);  // the twin: it does move
    }
}

TEST(MitsubaFiles, AReferenceMayPrecedeItsBsdfAndNameANestedOne) {
    const std::string body = scene(
        "  <shape type=\"rectangle\"><ref id=\"later\"/></shape>\n"
        "  <shape type=\"sphere\"><ref id=\"inner\"/></shape>\n"
        "  <shape type=\"cube\"><bsdf type=\"diffuse\" id=\"inner\"><rgb name=\"reflectance\" value=\"0.1\"/></bsdf>"
        "</shape>\n  <bsdf type=\"diffuse\" id=\"later\"><rgb name=\"reflectance\" value=\"0.7\"/></bsdf>\n");
    const SceneDescription s = loadScene(writeScene("forward", body), {}, "ao");
    EXPECT_EQ(test::frontAlbedo(s, s.meshes.at(0)).x, 0.7f);
    EXPECT_EQ(test::frontAlbedo(s, s.spheres.at(0)).x, 0.1f);
    EXPECT_EQ(test::frontAlbedo(s, s.meshes.at(1)).x, 0.1f);
    const std::string cycle = scene("  <shape type=\"cube\"><ref id=\"a\"/></shape>\n"
                                    "  <bsdf type=\"twosided\" id=\"a\"><ref id=\"b\"/></bsdf>\n"
                                    "  <bsdf type=\"twosided\" id=\"b\">\n    <ref id=\"a\"/></bsdf>\n");
    EXPECT_TRUE(contains(errorOf("cycle", cycle, "ao"), "refers to itself")) << errorOf("cycle", cycle, "ao");
    const std::string twice = scene(kRectangle + "  <bsdf type=\"diffuse\" id=\"a\"/>\n  <bsdf type=\"diffuse\" id=\"a\"/>\n");
    EXPECT_TRUE(contains(errorOf("twice", twice), "mcval_mitsuba_twice.xml:5: <bsdf>: the id \"a\" is already defined"))
        << errorOf("twice", twice);
    EXPECT_TRUE(contains(errorOf("missing", scene("  <shape type=\"cube\">\n<ref id=\"nowhere\"/></shape>\n")),
                         "mcval_mitsuba_missing.xml:4: <ref>: no <bsdf id=\"nowhere\"> in the file"));
}

TEST(MitsubaFiles, ABsdfNoShapeRefersToIsNotRead) {
    // As no integrator reads it: one of a type no integrator models loads under direct, with a note.
    const std::string body = scene(kRectangle + "  <bsdf type=\"principled\" id=\"unused\"/>\n");
    EXPECT_EQ(errorOf("unreferenced", body, "direct"), "");
    const std::string used = scene("  <shape type=\"cube\"><ref id=\"unused\"/></shape>\n  <bsdf type=\"principled\" "
                                   "id=\"unused\"/>\n");
    EXPECT_TRUE(contains(errorOf("referenced", used, "direct"), "mcval_mitsuba_referenced.xml:4: <bsdf>: unsupported bsdf"));
    EXPECT_EQ(errorOf("referenced", used, "ao"), "");  // ao reads no material
}

TEST(MitsubaFiles, TwosidedDiffuseIsDiffuseOnBothSides) {
    const std::string body = scene(
        "  <shape type=\"rectangle\"><bsdf type=\"twosided\"><bsdf type=\"diffuse\"><rgb name=\"reflectance\" "
        "value=\"0.3\"/></bsdf></bsdf></shape>\n  <bsdf type=\"twosided\" id=\"pair\"><bsdf type=\"diffuse\"/>"
        "<bsdf type=\"diffuse\"><float name=\"reflectance\" value=\"0.2\"/></bsdf></bsdf>\n"
        "  <shape type=\"cube\"><ref id=\"pair\"/></shape>\n  <shape type=\"sphere\"/>\n");
    const SceneDescription s = loadScene(writeScene("twosided", body), {}, "ao");
    EXPECT_EQ(test::frontAlbedo(s, s.meshes.at(0)).x, 0.3f);
    ASSERT_TRUE(test::backAlbedo(s, s.meshes.at(0)).has_value());
    EXPECT_EQ(test::backAlbedo(s, s.meshes.at(0))->z, 0.3f);
    EXPECT_EQ(test::frontAlbedo(s, s.meshes.at(1)).x, 0.5f);
    EXPECT_EQ(test::backAlbedo(s, s.meshes.at(1))->x, 0.2f);
    EXPECT_FALSE(test::backAlbedo(s, s.spheres.at(0)).has_value());
    // Around a bsdf we cannot model it is refused where the reflectance is read, skipped under normals and ao.
    const std::string plastic = scene("  <shape type=\"rectangle\"><bsdf type=\"twosided\">\n    <bsdf "
                                      "type=\"principled\"/></bsdf></shape>\n");
    EXPECT_EQ(errorOf("twosided_plastic", plastic), "");
    EXPECT_EQ(errorOf("twosided_plastic", plastic, "ao"), "");
    EXPECT_TRUE(contains(errorOf("twosided_plastic", plastic, "direct"), "mcval_mitsuba_twosided_plastic.xml:4:"));
}

TEST(MitsubaFiles, TheBackOfATwosidedSurfaceIsLitAndAOneSidedOneIsBlack) {
    // A rectangle seen from behind (to_world turns its normal away from the camera) under ao and simple.
    for (const char *integrator : {"ao", "simple"}) {
        double mean[2];
        for (int twoSided = 0; twoSided < 2; ++twoSided) {
            const std::string bsdf = twoSided ? "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf>"
                                              : "<bsdf type=\"diffuse\"/>";
            const std::string body =
                "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>"
                "<transform name=\"to_world\"><lookat origin=\"0, 0, -4\" target=\"0, 0, 0\"/></transform>"
                "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/>"
                "</film></sensor>\n  <shape type=\"rectangle\">" + bsdf + "</shape>\n"
                "  <emitter type=\"point\"><point name=\"position\" value=\"0, 0, -2\"/></emitter>\n</scene>\n";
            RenderOptions options;
            options.spp = 4;
            options.integrator = integrator;
            const RenderOutput out = render(loadScene(writeScene("back", body), {}, integrator), options);
            mean[twoSided] = 0.0;
            for (const float v : out.mean.rgb) mean[twoSided] += v / out.mean.rgb.size();
        }
        EXPECT_EQ(mean[0], 0.0) << integrator;
        EXPECT_GT(mean[1], 0.01) << integrator;
    }
}

TEST(MitsubaFiles, AMitsuba05FileIsUpgradedAsMitsuba3Upgrades) {
    const std::string shapes =
        "  <shape type=\"rectangle\"><transform name=\"toWorld\"><translate z=\"-1\"/></transform>"
        "<bsdf type=\"diffuse\"><rgb name=\"diffuseReflectance\" value=\"0.25\"/></bsdf></shape>\n"
        "  <integrator type=\"ao\"><boolean name=\"hideEmitters\" value=\"false\"/></integrator>\n";
    const std::string sensor = "<float name=\"nearClip\" value=\"0.5\"/><float name=\"farClip\" value=\"50\"/>"
                               "<string name=\"fovAxis\" value=\"y\"/>";
    const SceneDescription s = loadScene(writeScene("v05", scene(shapes, sensor, "0.5.0")));
    EXPECT_EQ(s.camera.nearClip, 0.5f);
    EXPECT_EQ(s.camera.farClip, 50.f);
    EXPECT_EQ(s.camera.fovAxis, "y");
    EXPECT_EQ(test::frontAlbedo(s, s.meshes.at(0)).x, 0.25f);
    EXPECT_EQ(s.meshes.at(0).positions.at(0).z, -1.f);
    EXPECT_EQ(s.hideEmitters, std::optional<bool>(false));
    // The version is each file's: a 0.5 file included by a 3.0 one is upgraded, and the 3.0 one is not.
    writeScene("v05_part", "<scene version=\"0.5.0\">" + shapes + "</scene>\n");
    const SceneDescription mixed = loadScene(
        writeScene("v3_includes_v05", scene("  <include filename=\"mcval_mitsuba_v05_part.xml\"/>\n")));
    EXPECT_EQ(test::frontAlbedo(mixed, mixed.meshes.at(0)).x, 0.25f);
    // A 3.0 file keeps its names, as Mitsuba 3 does: camelCase there is an unknown property.
    EXPECT_TRUE(contains(errorOf("v3_camel", scene(shapes, sensor)), "unsupported property \"farClip\""));
}

TEST(MitsubaFiles, MediaAndUnusedEmittersAreSkippedWhereTheIntegratorIgnoresThem) {
    const std::string body = scene(
        "  <medium type=\"homogeneous\" id=\"fog\"><rgb name=\"albedo\" value=\"0.5\"/></medium>\n"
        "  <shape type=\"rectangle\"><ref name=\"interior\" id=\"fog\"/><medium type=\"homogeneous\" "
        "name=\"exterior\"/><emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>\n"
        "  <emitter type=\"point\"><point name=\"position\" value=\"0, 0, 3\"/></emitter>\n",
        "<ref id=\"fog\"/>");
    for (const char *integrator : {"normals", "ao", "simple"}) {
        const SceneDescription s = loadScene(writeScene("media", body), {}, integrator);
        EXPECT_EQ(s.meshes.size(), 1u) << integrator;
    }
}

TEST(MitsubaFiles, DeeplyNestedBsdfsFailWithTheirLine) {
    // 2,000 nested twosided bsdfs: a clear error at the first one past the bound, not a stack overflow.
    std::string nested;
    for (int i = 0; i < 2000; ++i) nested += "<bsdf type=\"twosided\">\n";
    nested += "<bsdf type=\"diffuse\"/>";
    for (int i = 0; i < 2000; ++i) nested += "</bsdf>";
    const std::string message = errorOf("nested", scene("  <shape type=\"rectangle\">" + nested + "</shape>\n"), "ao");
    // The bsdf at depth d (the shape's own at 0, on line 3) stands on line 3 + d; the first refused is at 65.
    EXPECT_TRUE(contains(message, "mcval_mitsuba_nested.xml:68: <bsdf>:"))
        << message.substr(0, 200);
    EXPECT_TRUE(contains(message, "bsdfs nested (or referenced through one another) more than 64 deep"));
    // 2,000 twosided bsdfs each referring to the next: b0 on line 4, so b65 on line 69.
    std::string chain = "  <shape type=\"rectangle\"><ref id=\"b0\"/></shape>\n";
    for (int i = 0; i < 2000; ++i)
        chain += "  <bsdf type=\"twosided\" id=\"b" + std::to_string(i) + "\"><ref id=\"b" + std::to_string(i + 1) +
                 "\"/></bsdf>\n";
    chain += "  <bsdf type=\"diffuse\" id=\"b2000\"/>\n";
    const std::string refs = errorOf("chain", scene(chain), "ao");
    EXPECT_TRUE(contains(refs, "mcval_mitsuba_chain.xml:69: <bsdf>: bsdfs nested")) << refs.substr(0, 200);
}

TEST(MitsubaFiles, ACropWindowIsThatPartOfTheWholeFilm) {
    // The same pixels, bit for bit: the camera keeps the whole film's projection and each pixel its samples.
    const auto body = [](const std::string &crop, const std::string &filter) {
        return "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"><float name=\"fov\" value=\"60\"/>"
               "<transform name=\"to_world\"><lookat origin=\"0.3, 0.2, 3\" target=\"0, 0, 0\"/></transform>"
               "<film type=\"hdrfilm\"><integer name=\"width\" value=\"24\"/><integer name=\"height\" value=\"16\"/>" +
               crop + "<rfilter type=\"" + filter + "\"/></film></sensor>\n  <shape type=\"sphere\"/>\n"
               "  <shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"3\"/><translate z=\"-1\"/>"
               "</transform></shape>\n  <emitter type=\"point\"><point name=\"position\" value=\"1, 2, 2\"/>"
               "</emitter>\n</scene>\n";
    };
    const std::string crop = "<integer name=\"crop_offset_x\" value=\"5\"/><integer name=\"crop_offset_y\" value=\"3\"/>"
                             "<integer name=\"crop_width\" value=\"11\"/><integer name=\"crop_height\" value=\"9\"/>";
    RenderOptions options;
    options.spp = 8;
    options.integrator = "simple";
    const RenderOutput full = render(loadScene(writeScene("uncropped", body("", "box"))), options);
    const RenderOutput part = render(loadScene(writeScene("cropped", body(crop, "box"))), options);
    ASSERT_EQ(part.mean.width, 11);
    ASSERT_EQ(part.mean.height, 9);
    int differing = 0;
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 11; ++x)
            for (int c = 0; c < 3; ++c)
                differing += part.mean.rgb[3 * (y * 11 + x) + c] != full.mean.rgb[3 * ((y + 3) * 24 + x + 5) + c];
    EXPECT_EQ(differing, 0);
    // The twin: shifted by one pixel, the crop does not match.
    int shifted = 0;
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 11; ++x) shifted += part.mean.rgb[3 * (y * 11 + x)] != full.mean.rgb[3 * ((y + 3) * 24 + x + 6)];
    EXPECT_GT(shifted, 10);
    // With a gaussian filter, sample_border gives the window's edge pixels the samples around them that the
    // whole film gives them (the same values, summed in another order); without it they lack them.
    const std::string border = crop + "<boolean name=\"sample_border\" value=\"true\"/>";
    const RenderOutput wide = render(loadScene(writeScene("uncropped_g", body("", "gaussian"))), options);
    for (const bool sampleBorder : {true, false}) {
        const RenderOutput edged =
            render(loadScene(writeScene("bordered", body(sampleBorder ? border : crop, "gaussian"))), options);
        double worst = 0.0;
        for (int y = 0; y < 9; ++y)
            for (int x = 0; x < 11; ++x)
                for (int c = 0; c < 3; ++c) {
                    const float a = edged.mean.rgb[3 * (y * 11 + x) + c], b = wide.mean.rgb[3 * ((y + 3) * 24 + x + 5) + c];
                    worst = std::max(worst, double(std::abs(a - b)) / std::max(1e-3, double(std::abs(b))));
                }
        if (sampleBorder)
            EXPECT_LT(worst, 1e-5);
        else
            EXPECT_GT(worst, 1e-2);
    }
    const std::string outside = "<integer name=\"crop_offset_x\" value=\"20\"/>\n<integer name=\"crop_width\" value=\"5\"/>";
    EXPECT_TRUE(contains(errorOf("crop_outside", body(outside, "tent")), "mcval_mitsuba_crop_outside.xml:3:"));
    EXPECT_TRUE(contains(errorOf("crop_outside", body(outside, "tent")), "the crop window must lie within the film"));
}
