// path: Mitsuba's path tracer, checked against the furnace's closed form. Inside a closed sphere whose inner
// side is diffuse of albedo a and emits radiance 1, every ray sees 1 + a + ... + a^(d-1) with d = max_depth
// vertices, and 1 / (1 - a) without a limit (Nori's furnaces: 2 at a = 0.5, 5 at a = 0.8). Each strategy
// (emitter samples, BSDF samples, MIS) must give it, Russian roulette included; the planted twins of
// tests/cpp/path_twins_integrator.cpp (roulette without dividing by the survival probability, MIS that counts
// the light twice, a missing cosine, a max_depth off by one) must miss it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "embree_scene.h"
#include "error.h"
#include "integrators/registry.h"
#include "radiance_estimate.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

const char *kSensor = "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><film type=\"hdrfilm\">"
                      "<integer name=\"width\" value=\"8\"/><integer name=\"height\" value=\"8\"/></film></sensor>\n";

/// The furnace: a unit sphere at the origin, facing inward, diffuse of albedo `albedo`, emitting 1 inside.
SceneDescription furnace(const std::string &name, double albedo, const std::string &properties,
                         const std::string &integrator = "path") {
    const fs::path path = fs::temp_directory_path() / ("mcval_path_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n" << kSensor << "<integrator type=\"" << integrator << "\">"
                        << properties
                        << "</integrator>\n<shape type=\"sphere\"><boolean name=\"flip_normals\" value=\"true\"/>"
                        << "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"" << albedo << "\"/></bsdf>"
                        << "<emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n</scene>\n";
    return loadScene(path.string());
}

/// A diffuse plane (reflectance 0.5) of 20 x 20 at z = 0 facing +z under a disk light of radius 1.5 and
/// radiance 3 at z = 2, facing down.
SceneDescription diskOverPlane(const std::string &name, const std::string &properties) {
    const fs::path path = fs::temp_directory_path() / ("mcval_path_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n" << kSensor << "<integrator type=\"path\">" << properties
                        << "</integrator>\n<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"10\"/>"
                        << "</transform><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf></shape>\n"
                        << "<shape type=\"disk\"><boolean name=\"flip_normals\" value=\"true\"/><transform "
                        << "name=\"to_world\"><scale value=\"1.5\"/><translate value=\"0, 0, 2\"/></transform>"
                        << "<emitter type=\"area\"><rgb name=\"radiance\" value=\"3\"/></emitter></shape>\n</scene>\n";
    return loadScene(path.string());
}

/// The furnace's estimates, along a ray from near its centre.
Estimate estimate(const SceneDescription &scene, int n) {
    return mcval::estimate(scene, {0.1f, -0.2f, 0.05f}, normalize(Vec3f(0.3f, 0.4f, -0.8f)), n);
}

/// Within 5 standard errors and 0.5 %.
bool agrees(const Estimate &e, double expected) {
    return std::abs(e.mean - expected) <= 5.0 * e.error + 0.005 * expected;
}

/// 1 + a + ... + a^(d-1); d < 0: the whole series.
double partialSum(double a, int d) { return d < 0 ? 1.0 / (1.0 - a) : (1.0 - std::pow(a, d)) / (1.0 - a); }

std::string props(const std::string &strategy, int maxDepth, int rrDepth = 5) {
    return "<string name=\"strategy\" value=\"" + strategy + "\"/><integer name=\"max_depth\" value=\"" +
           std::to_string(maxDepth) + "\"/><integer name=\"rr_depth\" value=\"" + std::to_string(rrDepth) + "\"/>";
}

}  // namespace

TEST(Path, NorisFurnacesGiveTheirClosedFormsUnderEveryStrategy) {
    for (const double a : {0.5, 0.8}) {
        for (const char *strategy : {"mis", "ems", "mats"}) {
            const Estimate got = estimate(furnace("furnace", a, props(strategy, -1)), 20000);
            EXPECT_TRUE(agrees(got, 1.0 / (1.0 - a)))
                << "albedo " << a << " " << strategy << ": " << got.mean << " +- " << got.error;
        }
    }
}

TEST(Path, EachMaxDepthGivesItsPartialSum) {
    // Up to rr_depth no roulette: the partial sums exactly where the furnace is uniform (mats: every sample
    // collects the sphere's emission at each vertex; its noise is the BSDF sample's alone, none here).
    for (const int d : {1, 2, 3, 4}) {
        const Estimate got = estimate(furnace("depth", 0.5, props("mats", d, 8)), 200);
        EXPECT_NEAR(got.mean, partialSum(0.5, d), 1e-5) << "max_depth " << d;
        // Off by one either way is another partial sum, which the check must tell apart.
        EXPECT_GT(std::abs(got.mean - partialSum(0.5, d + 1)), 0.01);
        EXPECT_GT(std::abs(got.mean - partialSum(0.5, d - 1)), 0.01);
    }
    for (const int d : {2, 3, 7}) {
        for (const char *strategy : {"mis", "ems"}) {
            const Estimate got = estimate(furnace("depth_nee", 0.8, props(strategy, d, 3)), 20000);
            EXPECT_TRUE(agrees(got, partialSum(0.8, d))) << strategy << " max_depth " << d << ": " << got.mean;
        }
    }
    EXPECT_EQ(estimate(furnace("depth0", 0.5, props("mis", 0)), 10).mean, 0.0);
}

TEST(Path, RouletteWithoutDividingBySurvivalMissesTheFurnace) {
    // From the first bounce on (rr_depth 1), a path survives each bounce with probability min(throughput, 0.95).
    // Divided by it, every kept path carries throughput 1 and the estimate is right. Without the division the
    // throughput after k bounces stays a^k and the path lives on with probability a^(1 + 2 + ... + k): the
    // estimate falls to the sum of a^k a^(k(k+1)/2), 1.28 at a = 0.5, which the furnace tells apart.
    const double a = 0.5;
    double undivided = 0.0;
    for (int k = 0; k < 40; ++k) undivided += std::pow(a, k) * std::pow(a, k * (k + 1) / 2.0);
    const Estimate got = estimate(furnace("rr", a, props("mis", -1, 1)), 40000);
    EXPECT_TRUE(agrees(got, 1.0 / (1.0 - a))) << got.mean << " +- " << got.error;
    EXPECT_FALSE(agrees(got, undivided));
}

TEST(Path, EachPlantedWrongTwinMissesTheFurnace) {
    // The twins of tests/cpp/path_twins_integrator.cpp, where path itself gives the closed form.
    const std::string rr = "<integer name=\"rr_depth\" value=\"1\"/>";
    const struct {
        const char *twin;
        std::string properties;
        double expected;
    } cases[] = {{"path_rr_undivided", rr, 2.0},
                 {"path_double_mis", "", 2.0},
                 {"path_no_cosine", "<integer name=\"max_depth\" value=\"3\"/>", partialSum(0.5, 3)},
                 {"path_depth_plus_one", "<integer name=\"max_depth\" value=\"3\"/>", partialSum(0.5, 3)}};
    for (const auto &c : cases) {
        const Estimate right = estimate(furnace("right", 0.5, c.properties), 20000);
        EXPECT_TRUE(agrees(right, c.expected)) << c.twin << ": path gives " << right.mean;
        const Estimate wrong = estimate(furnace(c.twin, 0.5, c.properties, c.twin), 20000);
        EXPECT_FALSE(agrees(wrong, c.expected)) << c.twin << ": " << wrong.mean << " +- " << wrong.error;
    }
}

TEST(Path, HiddenEmittersAreNoVertexOfThePath) {
    // From above the disk, looking down through it at the plane: the disk's back (black, emitting downward
    // only) ends the path; with hide_emitters the camera ray passes through it, and max_depth 2 is then the
    // plane's direct light, rho / pi * pi L sin^2 alpha, as Mitsuba's (the pass-through is no vertex).
    const Vec3f above{0.f, 0.f, 3.f}, down{0.f, 0.f, -1.f};
    EXPECT_EQ(estimate(diskOverPlane("shown", props("mis", 2)), above, down, 100).mean, 0.0);
    const std::string hide = "<boolean name=\"hide_emitters\" value=\"true\"/>";
    const double direct = 0.5 * 3.0 * (1.5 * 1.5) / (1.5 * 1.5 + 2.0 * 2.0);
    const Estimate hidden = estimate(diskOverPlane("hidden", hide + props("mis", 2)), above, down, 40000);
    EXPECT_TRUE(agrees(hidden, direct)) << hidden.mean << " +- " << hidden.error << ", expected " << direct;
    EXPECT_EQ(estimate(diskOverPlane("hidden1", hide + props("mis", 1)), above, down, 100).mean, 0.0);
    // From below, the disk's emitting side: seen as its radiance, unless hidden (then the empty sky).
    const Vec3f below{0.f, 0.f, 0.5f}, up{0.f, 0.f, 1.f};
    EXPECT_NEAR(estimate(diskOverPlane("seen", props("mis", 1)), below, up, 10).mean, 3.0, 1e-6);
    EXPECT_EQ(estimate(diskOverPlane("seen_hidden", hide + props("mis", -1)), below, up, 100).mean, 0.0);
}

TEST(Path, RefusesSettingsMitsubaRefuses) {
    const auto errorOf = [](const std::string &properties) -> std::string {
        try {
            furnace("bad", 0.5, properties);
        } catch (const SceneError &e) {
            return e.what();
        }
        return "";
    };
    EXPECT_NE(errorOf("<integer name=\"max_depth\" value=\"-2\"/>").find("max_depth"), std::string::npos);
    EXPECT_NE(errorOf("<integer name=\"rr_depth\" value=\"0\"/>").find("rr_depth"), std::string::npos);
    EXPECT_NE(errorOf("<string name=\"strategy\" value=\"bdpt\"/>").find("mis (emitter and BSDF samples)"),
              std::string::npos);
    EXPECT_NE(errorOf("<integer name=\"samples\" value=\"2\"/>").find("samples"), std::string::npos);
    EXPECT_EQ(errorOf(props("ems", 3, 2)), "");
}
