// The integrator registry: every integrator's own file registers it, the test-only one included.
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "error.h"
#include "integrators/registry.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

TEST(IntegratorRegistry, ListsEveryLinkedIntegratorSorted) {
    // If the linker dropped an integrator's object file (a static library instead of the OBJECT
    // library), its name would be missing here.
    // every_emitter is the test binary's own (test_emitter_loader.cpp).
    EXPECT_EQ(integratorNames(),
              (std::vector<std::string>{"albedo", "ao", "ao_uniform", "every_emitter", "normals", "simple"}));
    EXPECT_EQ(integratorNameList(), "albedo, ao, ao_uniform, every_emitter, normals or simple");
    ASSERT_NE(findIntegrator("ao"), nullptr);
    EXPECT_EQ(findIntegrator("path"), nullptr);
    EXPECT_TRUE(findIntegrator("simple")->use.needsPointLight);
    EXPECT_FALSE(findIntegrator("normals")->use.readsReflectance);
    // The emitter kinds each reads: what the loader keeps for it, and skips with a note otherwise.
    EXPECT_EQ(findIntegrator("simple")->use.emitters, EmitterKinds{EmitterKind::Point});
    EXPECT_EQ(findIntegrator("ao")->use.emitters, EmitterKinds{EmitterKind::Constant});
    EXPECT_TRUE(findIntegrator("normals")->use.emitters.empty());
}

TEST(IntegratorRegistry, TheTestOnlyAlbedoRendersTheReflectance) {
    // plane_ao: a grey floor of reflectance 0.5 filling the view's lower half; the sky is 0.
    const std::string path = (fs::path(MCVAL_SOURCE_DIR) / "scenes" / "plane_ao.xml").string();
    const SceneDescription scene = loadScene(path, {{"res", "16"}}, "albedo");
    RenderOptions options;
    options.spp = 1;
    const RenderOutput out = render(scene, options);
    int floor = 0;
    for (float v : out.mean.rgb) {
        if (v != 0.f) {
            EXPECT_FLOAT_EQ(v, 0.5f);
            ++floor;
        }
    }
    EXPECT_GT(floor, 0);
}

TEST(IntegratorRegistry, UnknownNameListsTheChoices) {
    const std::string path = (fs::path(MCVAL_SOURCE_DIR) / "scenes" / "plane_ao.xml").string();
    SceneDescription scene = loadScene(path, {{"res", "8"}});
    RenderOptions options;
    options.integrator = "path";
    try {
        render(scene, options);
        FAIL() << "an unknown integrator rendered";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("unknown integrator \"path\": expected albedo, ao, ao_uniform, every_emitter, normals or simple"),
                  std::string::npos) << e.what();
    }
}

TEST(IntegratorRegistry, AoParsesItsOwnSamples) {
    // plane_ao with <integrator type="ao"> given samples="4": four occlusion rays per floor hit, where
    // ao's defaults (the same scene loaded for another integrator, rendered with ao) trace one.
    std::ifstream in(fs::path(MCVAL_SOURCE_DIR) / "scenes" / "plane_ao.xml");
    std::stringstream text;
    text << in.rdbuf();
    std::string xml = text.str();
    const std::string element = "<integrator type=\"$integrator\"/>";
    ASSERT_NE(xml.find(element), std::string::npos);
    xml.replace(xml.find(element), element.size(), "<integrator type=\"ao\"><integer name=\"samples\" value=\"4\"/></integrator>");
    const fs::path path = fs::temp_directory_path() / "mcval_test_ao_samples.xml";  // a rectangle: no mesh files
    std::ofstream(path) << xml;
    RenderOptions options;
    options.spp = 1;
    const uint64_t configured = render(loadScene(path.string(), {{"res", "8"}}), options).stats.shadowRays;
    options.integrator = "ao";
    const uint64_t defaults = render(loadScene(path.string(), {{"res", "8"}}, "normals"), options).stats.shadowRays;
    fs::remove(path);
    EXPECT_EQ(defaults, 64u);  // every pixel sees the floor
    EXPECT_EQ(configured, 4 * defaults);
}
