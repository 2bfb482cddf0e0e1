// The loader reads the emitters an integrator declares and skips the others with today's note: spot,
// directional and area emitters, with Mitsuba's parameter names and defaults; an emitter this renderer
// does not model is refused only where the integrator would be lit by it.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "error.h"
#include "load_error.h"
#include "integrators/registry.h"
#include "scene.h"
#include "xml_props.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

/// An integrator of the test binary alone that reads every kind of emitter (its image: the reflectance).
class EveryEmitterIntegrator final : public Integrator {
public:
    explicit EveryEmitterIntegrator(const EmbreeScene &embree) : m_embree(embree) {}
    Color Li(const Ray &, const Hit *hit, Sampler &, RayCounts &) const override {
        return hit ? m_embree.reflectance(hit->geom) : Color(0.f, 0.f, 0.f);
    }

private:
    const EmbreeScene &m_embree;
};

MCVAL_REGISTER_INTEGRATOR({
    "every_emitter",
    "the reflectance at the first hit, reading every emitter kind (test binary only)",
    SceneUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds::all(), /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        if (props) props->finish("no properties");
        return [](const SceneDescription &, const EmbreeScene &embree) {
            return std::make_unique<EveryEmitterIntegrator>(embree);
        };
    },
});

std::string writeScene(const std::string &name, const std::string &emitters) {
    const fs::path path = fs::temp_directory_path() / ("mcval_emitter_loader_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>"
                           "<film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
                           "<integer name=\"height\" value=\"8\"/></film></sensor>\n"
                           "<emitter type=\"point\"><point name=\"position\" value=\"0, 0, 3\"/></emitter>\n"
                        << emitters << "</scene>\n";
    return path.string();
}

std::string errorOf(const std::string &path, const std::string &integrator) { return test::loadError(path, integrator); }

const std::string kLights =
    "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"5\"/><float name=\"cutoff_angle\" value=\"30\"/>"
    "<transform name=\"to_world\"><translate value=\"1, 2, 3\"/></transform></emitter>\n"
    "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, -2\"/>"
    "<rgb name=\"irradiance\" value=\"2\"/></emitter>\n"
    "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"7\"/></emitter></shape>\n"
    "<shape type=\"disk\"/>\n";

}  // namespace

TEST(EmitterLoader, AnIntegratorThatReadsEveryKindGetsTheirModels) {
    const SceneDescription scene = loadScene(writeScene("all", kLights), {}, "every_emitter");
    ASSERT_EQ(scene.spotLights.size(), 1u);
    EXPECT_FLOAT_EQ(scene.spotLights[0].intensity.x, 5.f);
    EXPECT_FLOAT_EQ(scene.spotLights[0].cutoffAngle, 30.f);
    EXPECT_FLOAT_EQ(scene.spotLights[0].beamWidth, 22.5f);  // Mitsuba's default: 3/4 of the cutoff
    EXPECT_FLOAT_EQ(scene.spotLights[0].toWorld.point({0.f, 0.f, 0.f}).y, 2.f);
    ASSERT_EQ(scene.directionalLights.size(), 1u);
    EXPECT_FLOAT_EQ(scene.directionalLights[0].direction.z, -1.f);
    EXPECT_FLOAT_EQ(scene.directionalLights[0].irradiance.x, 2.f);
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_TRUE(scene.meshes[0].areaRadiance.has_value());
    EXPECT_FLOAT_EQ(scene.meshes[0].areaRadiance->x, 7.f);
    ASSERT_EQ(scene.disks.size(), 1u);
    EXPECT_FALSE(scene.disks[0].areaRadiance.has_value());
}

TEST(EmitterLoader, IntegratorsThatDoNotReadAKindSkipItWithTheirNote) {
    const std::string path = writeScene("skipped", kLights);
    for (const char *integrator : {"simple", "ao", "normals"}) {
        testing::internal::CaptureStderr();
        const SceneDescription scene = loadScene(path, {}, integrator);
        const std::string note = testing::internal::GetCapturedStderr();
        EXPECT_TRUE(scene.spotLights.empty()) << integrator;
        EXPECT_TRUE(scene.directionalLights.empty()) << integrator;
        EXPECT_FALSE(scene.meshes[0].areaRadiance.has_value()) << integrator;
        EXPECT_NE(note.find(std::string("skipped, not used by the ") + integrator + " integrator: <emitter "
                            "type=\"area\"> at line 6; <emitter type=\"spot\"> at line 4; <emitter "
                            "type=\"directional\"> at line 5"),
                  std::string::npos)
            << note;
    }
}

TEST(EmitterLoader, WhatAnIntegratorReadsIsCheckedWhatItSkipsIsNot) {
    const std::string badArea = writeScene(
        "bad_area", "<shape type=\"rectangle\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"-1\"/>"
                    "</emitter></shape>\n");
    EXPECT_EQ(errorOf(badArea, "simple"), "");
    EXPECT_NE(errorOf(badArea, "every_emitter").find("radiance"), std::string::npos);
    const std::string badSpot = writeScene(
        "bad_spot", "<emitter type=\"spot\"><float name=\"beam_width\" value=\"40\"/></emitter>\n"
                    "<shape type=\"rectangle\"/>\n");
    EXPECT_EQ(errorOf(badSpot, "ao"), "");
    EXPECT_NE(errorOf(badSpot, "every_emitter").find("beam_width"), std::string::npos);
    const std::string twoAreas = writeScene(
        "two_areas", "<shape type=\"rectangle\"><emitter type=\"area\"/><emitter type=\"area\"/></shape>\n");
    EXPECT_EQ(errorOf(twoAreas, "simple"), "");
    EXPECT_NE(errorOf(twoAreas, "every_emitter").find("one area emitter"), std::string::npos);
}

TEST(EmitterLoader, AnEmitterNotModelledIsRefusedOnlyWhereItWouldLightTheImage) {
    const std::string path = writeScene(
        "projector", "<emitter type=\"projector\"/>\n"
                     "<shape type=\"rectangle\"/>\n");
    EXPECT_EQ(errorOf(path, "simple"), "");
    const std::string error = errorOf(path, "every_emitter");
    EXPECT_NE(error.find(".xml:4:"), std::string::npos) << error;
    EXPECT_NE(error.find("does not model"), std::string::npos) << error;
}
