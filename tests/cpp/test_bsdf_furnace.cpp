// The gray furnace of each scattering BSDF: a plane of it under a constant emitter of radiance 1, nothing else.
// What a ray toward it sees after one scattering (path with max_depth 2, direct) is the BSDF's directional
// albedo at that angle, the mean weight of its samples, whatever its lobes (transmitted light escapes below the
// sheet to the same sky). So the integrators' emitter samples, BSDF samples, MIS weights and delta lobes are
// held against the BSDF's own sampling, material by material, as a scene file gives it.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "radiance_estimate.h"
#include "render.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

/// A 200 x 200 sheet at z = 0 (normal +z) with `bsdf`, under a constant emitter of radiance 1.
SceneDescription furnace(const std::string &name, const std::string &bsdf, const std::string &integrator) {
    const fs::path path = fs::temp_directory_path() / ("mcval_bsdf_furnace_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n  <integrator type=\"path\"><integer name=\"max_depth\" "
                           "value=\"2\"/></integrator>\n  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer "
                           "name=\"width\" value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n"
                           "  <emitter type=\"constant\"/>\n  <shape type=\"rectangle\"><transform name=\"to_world\">"
                           "<scale value=\"100\"/></transform>" << bsdf << "</shape>\n</scene>\n";
    return loadScene(path.string(), {}, integrator);
}

/// The mean weight of n samples of `bsdf` at wi (red channel), with its standard error.
Estimate albedo(const Bsdf &bsdf, const Vec3f &wi, int n) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.f, 1.f);
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const Vec2f u(uniform(rng), uniform(rng));
        const double w = bsdf.sample(wi, u, uniform(rng)).weight.x;
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

const char *kBsdfs[] = {
    "<bsdf type=\"diffuse\"/>",
    "<bsdf type=\"conductor\"><float name=\"eta\" value=\"0.2\"/><float name=\"k\" value=\"3.9\"/></bsdf>",
    "<bsdf type=\"roughconductor\"><float name=\"alpha\" value=\"0.3\"/><string name=\"distribution\" "
    "value=\"ggx\"/><float name=\"eta\" value=\"1.5\"/><float name=\"k\" value=\"2\"/></bsdf>",
    "<bsdf type=\"dielectric\"/>",
    "<bsdf type=\"roughdielectric\"><float name=\"alpha\" value=\"0.2\"/><string name=\"int_ior\" value=\"water\"/>"
    "</bsdf>",
    "<bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.6, 0.2, 0.1\"/></bsdf>",
    "<bsdf type=\"roughplastic\"><float name=\"alpha\" value=\"0.2\"/><boolean name=\"nonlinear\" value=\"true\"/>"
    "<rgb name=\"diffuse_reflectance\" value=\"0.8\"/></bsdf>",
    "<bsdf type=\"twosided\"><bsdf type=\"roughplastic\"><float name=\"alpha\" value=\"0.05\"/></bsdf></bsdf>",
};

/// The ray from above toward the origin at `degrees` from the normal, and its wi in the sheet's local frame.
struct View {
    Vec3f o, d;
};
View view(float degrees) {
    const float t = degrees * float(M_PI) / 180.f;
    const Vec3f d(-std::sin(t), 0.f, -std::cos(t));
    return {d * -10.f, d};
}

}  // namespace

TEST(BsdfFurnace, EachBsdfSeesItsOwnAlbedoThroughPathAndDirect) {
    int index = 0;
    for (const char *bsdf : kBsdfs) {
        for (const char *integrator : {"path", "direct"}) {
            const SceneDescription scene = furnace("b" + std::to_string(index), bsdf, integrator);
            const Bsdf &material = *scene.bsdfs.at(scene.meshes.at(0).bsdf);
            for (const float degrees : {0.f, 45.f, 75.f}) {
                const View v = view(degrees);
                const Estimate seen = estimate(scene, v.o, v.d, 10000);
                // The sheet's normal is +z: wi in its local frame is -d (isotropic BSDFs: any frame about z).
                const Estimate expected = albedo(material, -v.d, 100000);
                const double sigma = std::sqrt(seen.error * seen.error + expected.error * expected.error);
                EXPECT_NEAR(seen.mean, expected.mean, 5.0 * sigma + 1e-5)
                    << bsdf << " under " << integrator << " at " << degrees << " degrees";
            }
        }
        ++index;
    }
}

TEST(BsdfFurnace, TellsGlassOfOneIndexFromAnother) {
    // The check's power: bk7 rendered against water's albedo at 75 degrees (Fresnel 0.19 against 0.15 there).
    const SceneDescription bk7 = furnace("bk7", "<bsdf type=\"dielectric\"/>", "path");
    const SceneDescription water =
        furnace("water", "<bsdf type=\"dielectric\"><string name=\"int_ior\" value=\"water\"/></bsdf>", "path");
    const View v = view(75.f);
    const Estimate seen = estimate(bk7, v.o, v.d, 10000);
    const Estimate wrong = albedo(*water.bsdfs.at(water.meshes.at(0).bsdf), -v.d, 100000);
    EXPECT_GT(std::abs(seen.mean - wrong.mean), 10.0 * std::sqrt(seen.error * seen.error + wrong.error * wrong.error));
}
