// The scattering BSDFs as a scene file gives them (renderer/scene_bsdfs.h): each type loads under direct and path
// with Mitsuba's defaults and named indices, is refused by simple (Lambertian albedos only) and skipped by ao; a
// parameter given in a form the renderer does not read (a texture, anisotropy, a named conductor) is refused with
// its line where the material is read and skipped where it is not; a malformed one is an error everywhere.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "error.h"
#include "load_error.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

/// A scene whose one sphere has `bsdf` (the element's text; its first line is line 5), lit by a constant emitter.
std::string writeScene(const std::string &name, const std::string &bsdf) {
    const fs::path path = fs::temp_directory_path() / ("mcval_scene_bsdfs_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer "
                           "name=\"width\" value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n"
                           "  <emitter type=\"constant\"/>\n  <shape type=\"sphere\">\n"
                        << bsdf << "\n  </shape>\n</scene>\n";
    return path.string();
}

std::string errorOf(const std::string &path, const std::string &integrator) { return test::loadError(path, integrator); }

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }

/// The sphere's BSDF in the scene file at `path` loaded for `integrator` (it outlives the scene).
std::shared_ptr<const Bsdf> sphereBsdf(const std::string &path, const std::string &integrator = "path") {
    const SceneDescription scene = loadScene(path, {}, integrator);
    return scene.bsdfs.at(scene.spheres.at(0).bsdf);
}

/// The Fresnel reflectance at normal incidence of a smooth interface, as its delta samples split: u.x below it
/// reflects.
float normalReflectance(const Bsdf &bsdf) {
    float lo = 0.f, hi = 1.f;
    for (int i = 0; i < 40; ++i) {
        const float mid = 0.5f * (lo + hi);
        (bsdf.sample(Vec3f(0.f, 0.f, 1.f), Vec2f(mid, 0.5f)).wo.z > 0.f ? lo : hi) = mid;
    }
    return lo;
}

float fresnelAtNormal(float eta) { return (eta - 1.f) * (eta - 1.f) / ((eta + 1.f) * (eta + 1.f)); }

}  // namespace

TEST(SceneBsdfs, EachTypeLoadsUnderDirectAndPathAndIsRefusedBySimpleAndSkippedByAo) {
    for (const char *type : {"conductor", "roughconductor", "dielectric", "roughdielectric", "plastic", "roughplastic"}) {
        const std::string path = writeScene(type, std::string("    <bsdf type=\"") + type + "\"/>");
        for (const char *integrator : {"direct", "path", "ao", "normals"})
            EXPECT_EQ(errorOf(path, integrator), "") << type << " " << integrator;
        EXPECT_FALSE(sphereBsdf(path)->lambertianAlbedo(true).has_value()) << type;
        const std::string pointLit = writeScene(std::string(type) + "_simple",
                                                std::string("    <bsdf type=\"") + type + "\"/>\n  </shape>\n  <emitter "
                                                "type=\"point\"/>\n  <shape type=\"rectangle\">");
        const std::string refused = errorOf(pointLit, "simple");
        EXPECT_TRUE(contains(refused, ":5:") && contains(refused, "direct and path read it")) << refused;
    }
}

TEST(SceneBsdfs, IndicesOfRefractionAreNumbersOrMitsubasNamesWithItsDefaults) {
    // dielectric: bk7 in air by default; a name is looked up without case; a number is taken as given.
    const auto reflectance = [](const std::string &name, const std::string &bsdf) {
        return normalReflectance(*sphereBsdf(writeScene(name, bsdf)));
    };
    EXPECT_NEAR(reflectance("bk7", "<bsdf type=\"dielectric\"/>"), fresnelAtNormal(1.5046f / 1.000277f), 1e-5f);
    EXPECT_NEAR(reflectance("diamond", "<bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"Diamond\"/>"
                                       "<string name=\"ext_ior\" value=\"vacuum\"/></bsdf>"),
                fresnelAtNormal(2.419f), 1e-5f);
    EXPECT_NEAR(reflectance("number", "<bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"1.33\"/></bsdf>"),
                fresnelAtNormal(1.33f / 1.000277f), 1e-5f);
    const std::string unknown = errorOf(
        writeScene("unknown_ior", "    <bsdf type=\"dielectric\">\n      <string name=\"int_ior\" value=\"glass\"/>\n"
                                  "    </bsdf>"), "ao");
    EXPECT_TRUE(contains(unknown, ":6:") && contains(unknown, "unknown index of refraction \"glass\"")) << unknown;
    const std::string same = errorOf(
        writeScene("same_ior", "    <bsdf type=\"dielectric\"><float name=\"int_ior\" value=\"1.000277\"/></bsdf>"),
        "path");
    EXPECT_TRUE(contains(same, "must differ")) << same;
}

TEST(SceneBsdfs, PlasticReadsAnRgbDiffuseReflectanceChannelByChannel) {
    const auto loaded = sphereBsdf(writeScene("plastic_rgb", "<bsdf type=\"roughplastic\"><rgb "
                                                             "name=\"diffuse_reflectance\" value=\"0.1, 0.2, 0.4\"/>"
                                                             "<float name=\"alpha\" value=\"0.3\"/></bsdf>"));
    const Bsdf &bsdf = *loaded;
    // Away from the specular lobe the diffuse base dominates: each channel in proportion to its reflectance.
    const Color f = bsdf.eval(Vec3f(0.f, 0.f, 1.f), normalize(Vec3f(0.9f, 0.f, 0.2f)));
    const Color g = bsdf.eval(Vec3f(0.f, 0.f, 1.f), normalize(Vec3f(-0.9f, 0.1f, 0.3f)));
    EXPECT_GT(f.z, 1.9f * f.y);
    EXPECT_GT(f.y, 1.9f * f.x);
    EXPECT_NEAR((f.z - f.y) / (f.y - f.x), 2.f, 1e-3f);  // the gray specular part cancels
    EXPECT_NEAR((g.z - g.y) / (g.y - g.x), 2.f, 1e-3f);
}

TEST(SceneBsdfs, AFormTheRendererDoesNotReadIsRefusedWhereReadAndSkippedElsewhere) {
    const struct {
        const char *name, *bsdf, *says;
    } cases[] = {
        {"textured_alpha", "    <bsdf type=\"roughconductor\">\n      <texture name=\"alpha\" type=\"checkerboard\"/>\n"
                           "    </bsdf>", "a checkerboard texture (alpha) at line 6"},
        {"anisotropic", "    <bsdf type=\"roughconductor\"><float name=\"alpha_u\" value=\"0.1\"/><float "
                        "name=\"alpha_v\" value=\"0.3\"/></bsdf>", "anisotropic roughness"},
        {"named_conductor", "    <bsdf type=\"conductor\">\n      <string name=\"material\" value=\"Au\"/>\n    </bsdf>",
         "the named conductor \"Au\""},
        {"spectral_ior", "    <bsdf type=\"dielectric\">\n      <spectrum name=\"int_ior\" value=\"400:1.5, 700:1.4\"/>"
                         "\n    </bsdf>", "a per-wavelength <spectrum> (int_ior) at line 6"},
        {"rgb_eta", "    <bsdf type=\"conductor\"><rgb name=\"eta\" value=\"0.2, 0.9, 1.1\"/></bsdf>",
         "eta that differs by channel"},
        {"tinted_glass", "    <bsdf type=\"dielectric\"><rgb name=\"specular_transmittance\" value=\"0.5\"/></bsdf>",
         "specular_transmittance other than 1"},
    };
    for (const auto &c : cases) {
        const std::string path = writeScene(c.name, c.bsdf);
        const std::string refused = errorOf(path, "path");
        EXPECT_TRUE(contains(refused, ":5:") && contains(refused, c.says)) << c.name << ": " << refused;
        EXPECT_EQ(errorOf(path, "ao"), "") << c.name;
        EXPECT_EQ(errorOf(path, "normals"), "") << c.name;
    }
}

TEST(SceneBsdfs, MalformedParametersFailWithTheirLine) {
    const std::string distribution = errorOf(
        writeScene("distribution", "    <bsdf type=\"roughdielectric\">\n      <string name=\"distribution\" "
                                   "value=\"phong\"/>\n    </bsdf>"), "ao");
    EXPECT_TRUE(contains(distribution, ":6:") && contains(distribution, "beckmann or ggx")) << distribution;
    const std::string both = errorOf(
        writeScene("both_alphas", "    <bsdf type=\"roughconductor\"><float name=\"alpha\" value=\"0.1\"/><float "
                                  "name=\"alpha_u\" value=\"0.1\"/></bsdf>"), "path");
    EXPECT_TRUE(contains(both, "not both")) << both;
    const std::string unknown = errorOf(
        writeScene("unknown_property", "    <bsdf type=\"plastic\"><float name=\"roughness\" value=\"0.1\"/></bsdf>"),
        "path");
    EXPECT_TRUE(contains(unknown, "roughness")) << unknown;
    // Mitsuba's twosided mirrors directions to the front, which a transmitted one would leave.
    const std::string twosided = errorOf(
        writeScene("twosided_glass", "    <bsdf type=\"twosided\">\n      <bsdf type=\"dielectric\"/>\n    </bsdf>"),
        "ao");
    EXPECT_TRUE(contains(twosided, ":6:") && contains(twosided, "transmit no light")) << twosided;
}

TEST(SceneBsdfs, TwosidedRoughPlasticReflectsOnBothSides) {
    const auto loaded = sphereBsdf(writeScene("twosided_plastic", "<bsdf type=\"twosided\"><bsdf type=\"roughplastic\"/>"
                                                                  "</bsdf>"));
    const Bsdf &bsdf = *loaded;
    const Color front = bsdf.eval(normalize(Vec3f(0.3f, 0.f, 1.f)), normalize(Vec3f(-0.2f, 0.4f, 1.f)));
    const Color back = bsdf.eval(normalize(Vec3f(0.3f, 0.f, -1.f)), normalize(Vec3f(-0.2f, 0.4f, -1.f)));
    EXPECT_GT(front.x, 0.f);
    EXPECT_FLOAT_EQ(front.x, back.x);
    const BsdfSample s = bsdf.sample(normalize(Vec3f(0.3f, 0.f, -1.f)), Vec2f(0.7f, 0.4f), 0.9f);
    EXPECT_LT(s.wo.z, 0.f);
}
