// direct: Mitsuba's direct illumination, checked against closed forms at a point of a diffuse plane: under a
// disk, a rectangle, a sphere, a point light and the environment, the emitter-sampling, BSDF-sampling and
// MIS settings each estimate the same radiance; the camera sees an emitter unless hide_emitters; and the
// wrong twin (MIS weights that double-count: both strategies at full weight) fails the same check.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "bsdfs/conductor.h"
#include "bsdfs/roughconductor.h"
#include "embree_scene.h"
#include "error.h"
#include "integrators/registry.h"
#include "radiance_estimate.h"
#include "scene.h"
#include "warp.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

const char *kSensor = "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><film type=\"hdrfilm\">"
                      "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film></sensor>\n";
/// A diffuse plane (reflectance 0.5) of 20 x 20 at z = 0, facing +z.
const char *kPlane = "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"10\"/></transform>"
                     "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf></shape>\n";
constexpr double kRho = 0.5;

/// A scene: the plane, `lights`, and direct with `properties`.
SceneDescription load(const std::string &name, const std::string &lights, const std::string &properties) {
    const fs::path path = fs::temp_directory_path() / ("mcval_direct_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n" << kSensor << "<integrator type=\"direct\">" << properties
                        << "</integrator>\n" << kPlane << lights << "</scene>\n";
    return loadScene(path.string());
}

std::string samples(int emitter, int bsdf) {
    return "<integer name=\"emitter_samples\" value=\"" + std::to_string(emitter) +
           "\"/><integer name=\"bsdf_samples\" value=\"" + std::to_string(bsdf) + "\"/>";
}

/// Whether the estimate agrees with the expected value: within 5 standard errors and 1 %.
bool agrees(const Estimate &e, double expected) {
    return std::abs(e.mean - expected) <= 5.0 * e.error + 0.01 * expected;
}

/// The settings direct is checked in: emitter sampling only, BSDF sampling only, MIS, and MIS with more of each.
const std::pair<int, int> kSettings[] = {{1, 0}, {0, 1}, {1, 1}, {2, 3}};

/// Radiance leaving the plane at the origin toward +z under `lights` (irradiance E there): rho / pi E.
void expectEveryStrategy(const std::string &name, const std::string &lights, double irradiance) {
    const double expected = kRho / kPi * irradiance;
    for (const auto &[e, b] : kSettings) {
        const Estimate got = estimate(load(name, lights, samples(e, b)), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 40000);
        EXPECT_TRUE(agrees(got, expected)) << name << " emitter_samples " << e << " bsdf_samples " << b << ": "
                                           << got.mean << " +- " << got.error << ", expected " << expected;
    }
}

const std::string kDisk = "<shape type=\"disk\"><boolean name=\"flip_normals\" value=\"true\"/><transform "
                          "name=\"to_world\"><scale value=\"1.5\"/><translate value=\"0, 0, 2\"/></transform>"
                          "<emitter type=\"area\"><rgb name=\"radiance\" value=\"3\"/></emitter></shape>\n";

}  // namespace

TEST(Direct, UnderADiskEveryStrategyGivesTheClosedForm) {
    // E = pi L sin^2 alpha on the disk's axis.
    expectEveryStrategy("disk", kDisk, kPi * 3.0 * (1.5 * 1.5) / (1.5 * 1.5 + 2.0 * 2.0));
}

TEST(Direct, UnderARectangleEveryStrategyGivesTheClosedForm) {
    const std::string rectangle = "<shape type=\"rectangle\"><transform name=\"to_world\"><scale x=\"1\" y=\"0.6\"/>"
                                  "<rotate x=\"1\" angle=\"180\"/><translate value=\"0, 0, 1.3\"/></transform>"
                                  "<emitter type=\"area\"><rgb name=\"radiance\" value=\"2\"/></emitter></shape>\n";
    const double x = 1.0 / 1.3, y = 0.6 / 1.3;
    const double e = 2.0 * 2.0 *
                     (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                      y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)));
    expectEveryStrategy("rectangle", rectangle, e);
}

TEST(Direct, UnderASphereEveryStrategyGivesTheClosedForm) {
    const std::string sphere = "<shape type=\"sphere\"><point name=\"center\" value=\"0, 0, 3\"/>"
                               "<emitter type=\"area\"><rgb name=\"radiance\" value=\"4\"/></emitter></shape>\n";
    expectEveryStrategy("sphere", sphere, kPi * 4.0 / 9.0);  // pi L (r / D)^2
}

TEST(Direct, UnderTheEnvironmentEveryStrategyGivesTheClosedForm) {
    expectEveryStrategy("environment", "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"2\"/></emitter>\n",
                        kPi * 2.0);
}

TEST(Direct, APointLightIsSampledAloneWhateverTheSampleCounts) {
    // A delta light: only emitter samples find it, each at full weight over their count; BSDF samples add 0.
    const std::string point = "<emitter type=\"point\"><point name=\"position\" value=\"0, 0, 2\"/>"
                              "<rgb name=\"intensity\" value=\"8\"/></emitter>\n";
    const double expected = kRho / kPi * 8.0 / 4.0;
    for (const auto &[e, b] : {std::pair<int, int>{1, 0}, {1, 1}, {4, 2}}) {
        const Estimate got = estimate(load("point", point, samples(e, b)), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 100);
        EXPECT_NEAR(got.mean, expected, 1e-5 * expected) << e << " " << b;
    }
    EXPECT_EQ(estimate(load("point_bsdf", point, samples(0, 1)), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 100).mean, 0.0);
}

TEST(Direct, DoubleCountedMisWeightsFailTheSameCheck) {
    // Emitter sampling and BSDF sampling, each at full weight and added: twice the radiance.
    const double expected = kRho * 3.0 * (1.5 * 1.5) / (1.5 * 1.5 + 2.0 * 2.0);
    const Estimate ems = estimate(load("ems", kDisk, samples(1, 0)), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 40000);
    const Estimate mats = estimate(load("mats", kDisk, samples(0, 1)), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 40000);
    EXPECT_TRUE(agrees(ems, expected));
    EXPECT_TRUE(agrees(mats, expected));
    const Estimate doubled{ems.mean + mats.mean, std::hypot(ems.error, mats.error)};
    EXPECT_FALSE(agrees(doubled, expected));
}

TEST(Direct, TheCameraSeesAnEmitterUnlessHideEmitters) {
    // Looking up at the disk's emitting side from below it.
    const Estimate seen = estimate(load("seen", kDisk, ""), {0.f, 0.f, 0.5f}, {0.f, 0.f, 1.f}, 100);
    EXPECT_NEAR(seen.mean, 3.0, 1e-6);
    const Estimate hidden =
        estimate(load("hidden", kDisk, "<boolean name=\"hide_emitters\" value=\"true\"/>"), {0.f, 0.f, 0.5f},
                 {0.f, 0.f, 1.f}, 100);
    EXPECT_EQ(hidden.mean, 0.0);  // through the disk, into the empty sky
    // The environment likewise.
    const std::string sky = "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"2\"/></emitter>\n";
    EXPECT_NEAR(estimate(load("sky", sky, ""), {0.f, 0.f, 0.5f}, {0.f, 0.f, 1.f}, 10).mean, 2.0, 1e-6);
    EXPECT_EQ(estimate(load("sky_hidden", sky, "<boolean name=\"hide_emitters\" value=\"true\"/>"),
                       {0.f, 0.f, 0.5f}, {0.f, 0.f, 1.f}, 10).mean, 0.0);
}

TEST(Direct, AMirrorReflectsTheEnvironmentThroughItsBsdfSamplesAtFullWeight) {
    // The plane made a smooth conductor (a delta lobe, its pdf infinite): every BSDF sample finds the sky at
    // F(1) times the specular reflectance, with the whole MIS weight (no emitter sample can find that
    // direction); emitter samples find nothing (the lobe has no value off its direction), as Mitsuba's.
    const std::string sky = "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"2\"/></emitter>\n";
    const auto mirror = std::make_shared<ConductorBsdf>(0.2f, 3.f, Color(0.5f, 0.5f, 0.5f));
    const double expected = 0.5 * fresnelConductor(1.f, 0.2f, 3.f) * 2.0;
    for (const auto &[e, b] : {std::pair<int, int>{0, 1}, {1, 1}, {2, 3}, {1, 0}}) {
        SceneDescription scene = load("mirror", sky, samples(e, b));
        for (auto &bsdf : scene.bsdfs) bsdf = mirror;
        const Estimate got = estimate(scene, {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 16);
        EXPECT_NEAR(got.mean, b > 0 ? expected : 0.0, 1e-5) << e << " " << b;
    }
}

TEST(Direct, RefusesSampleCountsMitsubaRefuses) {
    const auto errorOf = [](const std::string &properties) -> std::string {
        try {
            load("bad", kDisk, properties);
        } catch (const SceneError &e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(errorOf(samples(0, 0)).find("at least one"), std::string::npos);
    EXPECT_NE(errorOf("<integer name=\"shading_samples\" value=\"2\"/>" + samples(1, 1)).find("not both"),
              std::string::npos);
    EXPECT_NE(errorOf(samples(-1, 1)).find("emitter_samples"), std::string::npos);
    EXPECT_EQ(errorOf("<integer name=\"shading_samples\" value=\"3\"/>"), "");
}

TEST(Direct, SpotAndDirectionalLightsLightAsMitsubaDefinesThem) {
    EXPECT_TRUE(findIntegrator("direct")->use.emitters == EmitterKinds::all());
    // On the spot's axis its full intensity, I / r^2; a directional light's irradiance times the cosine (1).
    const std::string spot = "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"8\"/><transform "
                             "name=\"to_world\"><lookat origin=\"0, 0, 2\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>"
                             "</transform></emitter>\n";
    EXPECT_NEAR(estimate(load("spot", spot, ""), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 10).mean, kRho / kPi * 2.0,
                1e-5);
    const std::string sun = "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, -1\"/>"
                            "<rgb name=\"irradiance\" value=\"3\"/></emitter>\n";
    EXPECT_NEAR(estimate(load("sun", sun, ""), {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 10).mean, kRho / kPi * 3.0, 1e-5);
    // An emitter it does not model would light its image: refused.
    EXPECT_THROW(load("projector", "<emitter type=\"projector\"/>\n", ""), SceneError);
}
