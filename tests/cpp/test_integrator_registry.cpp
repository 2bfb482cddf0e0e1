// The integrator registry: every integrator's own file registers it, the test-only one included.
#include <filesystem>

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
    EXPECT_EQ(integratorNames(), (std::vector<std::string>{"albedo", "ao", "normals", "simple"}));
    EXPECT_EQ(integratorNameList(), "albedo, ao, normals or simple");
    ASSERT_NE(findIntegrator("ao"), nullptr);
    EXPECT_EQ(findIntegrator("path"), nullptr);
    EXPECT_TRUE(findIntegrator("simple")->use.needsPointLight);
    EXPECT_FALSE(findIntegrator("normals")->use.readsReflectance);
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
        EXPECT_NE(std::string(e.what()).find("unknown integrator \"path\": expected albedo, ao, normals or simple"),
                  std::string::npos) << e.what();
    }
}
