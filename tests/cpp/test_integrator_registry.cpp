// The integrator registry: every integrator's own file registers it, the test-only one included.
#include <algorithm>
#include <cctype>
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

namespace {

/// The name a registration at `at` (just past "MCVAL_REGISTER_INTEGRATOR({") spells: blanks, then a quoted
/// [A-Za-z0-9_]+; empty if it spells something else. (Scanned by hand: <regex> alone doubles this file's compile.)
std::string quotedName(const std::string &source, size_t at) {
    while (at < source.size() && std::isspace(static_cast<unsigned char>(source[at]))) ++at;
    if (at >= source.size() || source[at] != '"') return {};
    const size_t begin = ++at;
    while (at < source.size() && (std::isalnum(static_cast<unsigned char>(source[at])) || source[at] == '_')) ++at;
    return at < source.size() && source[at] == '"' && at > begin ? source.substr(begin, at - begin) : std::string();
}

/// The names the given source files register with MCVAL_REGISTER_INTEGRATOR, as written there.
std::vector<std::string> registeredIn(const std::vector<fs::path> &files) {
    const std::string macro = "MCVAL_REGISTER_INTEGRATOR({";
    std::vector<std::string> names;
    for (const fs::path &file : files) {
        std::ifstream in(file);
        std::stringstream text;
        text << in.rdbuf();
        const std::string source = text.str();
        for (size_t at = source.find(macro); at != std::string::npos; at = source.find(macro, at + 1)) {
            std::string name = quotedName(source, at + macro.size());
            if (!name.empty()) names.push_back(std::move(name));
        }
    }
    return names;
}

/// Every integrator this test binary links: the product's (renderer/integrators/) and the test-only ones.
std::vector<std::string> linkedIntegrators() {
    const fs::path root(MCVAL_SOURCE_DIR);
    std::vector<fs::path> files;
    for (const auto &entry : fs::directory_iterator(root / "renderer" / "integrators"))
        if (entry.path().extension() == ".cpp") files.push_back(entry.path());
    // tests/cpp/*_integrator.cpp, as CMake globs them, and this binary's own every_emitter.
    for (const auto &entry : fs::directory_iterator(root / "tests" / "cpp")) {
        const std::string name = entry.path().filename().string();
        const std::string suffix = "_integrator.cpp";
        if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
            files.push_back(entry.path());
    }
    files.push_back(root / "tests" / "cpp" / "test_emitter_loader.cpp");
    std::vector<std::string> names = registeredIn(files);
    std::sort(names.begin(), names.end());
    return names;
}

/// "a, b or c", written out independently of the registry's own integratorNameList.
std::string joined(const std::vector<std::string> &names) {
    std::string list;
    for (size_t i = 0; i < names.size(); ++i) list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return list;
}

}  // namespace

TEST(IntegratorRegistry, ListsEveryLinkedIntegratorSorted) {
    // If the linker dropped an integrator's object file (a static library instead of the OBJECT
    // library), its name would be missing here: the list is the one the source files register.
    // every_emitter is the test binary's own (test_emitter_loader.cpp).
    const std::vector<std::string> linked = linkedIntegrators();
    for (const char *name : {"albedo", "ao", "ao_uniform", "every_emitter", "normals", "simple"})
        EXPECT_NE(std::find(linked.begin(), linked.end(), name), linked.end()) << name;
    EXPECT_EQ(integratorNames(), linked);
    EXPECT_EQ(integratorNameList(), joined(linked));
    ASSERT_NE(findIntegrator("ao"), nullptr);
    ASSERT_NE(findIntegrator("path"), nullptr);
    EXPECT_EQ(findIntegrator("bdpt"), nullptr);
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
    options.integrator = "bdpt";
    try {
        render(scene, options);
        FAIL() << "an unknown integrator rendered";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("unknown integrator \"bdpt\": expected " + joined(linkedIntegrators())),
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
