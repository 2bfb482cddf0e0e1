// The envmap emitter: its radiance is Mitsuba 3's (values Mitsuba 3.9.1's scalar_rgb envmap gives for the same
// image, direction and transform); its samples' densities are pdf() and its estimate of the light arriving from
// every direction is the uniform sphere's, where the twin without the sin(theta) Jacobian is not; under `direct`
// and `path` a plane it lights shows the closed form; and the loader's refusals name file, line and cause.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include "emitters/envmap.h"
#include "emitters/scene_emitters.h"
#include "error.h"
#include "load_error.h"
#include "radiance_estimate.h"
#include "temp_files.h"
#include "warp.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

constexpr const char *kPrefix = "mcval_envmap_";
fs::path folder() { return test::tempFolder(kPrefix); }
const auto *const kCleanup =
    ::testing::AddGlobalTestEnvironment(new test::TempFolderCleanup(test::tempFolderPath(kPrefix)));

/// A float RGB OpenEXR file of width x height pixels (`rgb` row by row from the top), in the test's folder.
std::string writeExr(const std::string &name, int width, int height, const std::vector<float> &rgb) {
    const std::string path = (folder() / name).string();
    Imf::Header header(width, height);
    Imf::FrameBuffer fb;
    static const char *names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, const_cast<char *>(reinterpret_cast<const char *>(rgb.data() + c)),
                                       3 * sizeof(float), 3 * sizeof(float) * size_t(width)));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(height);
    return path;
}

/// Pixel (x, y) of a width x height image = (x + 1, 10 (y + 1), 0.5): the image the Mitsuba values were taken of.
RgbImage probeImage() {
    RgbImage image;
    image.width = 4;
    image.height = 3;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) image.rgb.insert(image.rgb.end(), {float(x + 1), 10.f * float(y + 1), 0.5f});
    return image;
}

Color radianceAlong(const Emitter &e, Vec3f d) { return e.eval(escaped(normalize(d))); }

/// An image that is bright in a few places and dim elsewhere (a sun, a window), 32 x 16.
EnvironmentMap lumpyMap() {
    auto image = std::make_shared<RgbImage>();
    image->width = 32;
    image->height = 16;
    std::mt19937 rng(7);
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x) {
            const float base = 0.05f + 0.1f * float(rng() % 10);
            const float sun = (x == 5 && y == 3) ? 400.f : (x == 20 && y == 12 ? 60.f : 0.f);
            image->rgb.insert(image->rgb.end(), {base + sun, base, 0.5f * base + sun});
        }
    EnvironmentMap map;
    map.image = image;
    map.toWorld = Transform::rotate({1.f, 0.f, 0.f}, 90.f);
    return map;
}

}  // namespace

TEST(Envmap, ItsRadianceIsMitsubasBilinearLookup) {
    EnvironmentMap map;
    map.image = std::make_shared<RgbImage>(probeImage());
    const EnvmapEmitter plain(map);
    map.scale = 2.f;
    map.toWorld = Transform::rotate({0.f, 1.f, 0.f}, 90.f);
    const EnvmapEmitter turned(map);
    struct Case {
        Vec3f d;
        Color plain, turned;
    };
    const Case cases[] = {
        {{0.f, 0.f, -1.f}, {2.5f, 20.f, 0.5f}, {3.f, 40.f, 1.f}},
        {{1.f, 0.f, 0.f}, {1.5f, 20.f, 0.5f}, {5.f, 40.f, 1.f}},
        {{0.3f, 0.5f, -0.8f}, {1.8148f, 16.6293f, 0.5f}, {3.4568f, 33.2586f, 1.f}},
        {{-0.6f, -0.7f, 0.2f}, {3.29517f, 25.3224f, 0.5f}, {6.229f, 50.6449f, 1.f}},
    };
    for (const Case &c : cases) {
        const Color a = radianceAlong(plain, c.d), b = radianceAlong(turned, c.d);
        for (int k = 0; k < 3; ++k) {
            EXPECT_NEAR((&a.x)[k], (&c.plain.x)[k], 1e-3f * (&c.plain.x)[k]) << c.d.x << " " << c.d.y << " " << k;
            EXPECT_NEAR((&b.x)[k], (&c.turned.x)[k], 1e-3f * (&c.turned.x)[k]) << c.d.x << " " << c.d.y << " " << k;
        }
    }
}

TEST(Envmap, EachSampleCarriesItsDensityAndRadianceOverIt) {
    const EnvmapEmitter e(lumpyMap());
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    int disagree = 0, otherRadiance = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        const EmitterSample s = e.sample({}, {u(rng), u(rng)});
        ASSERT_GT(s.pdf, 0.f);
        ASSERT_TRUE(std::isinf(s.dist));
        EXPECT_FALSE(s.delta);
        const float pdf = e.pdf({}, escaped(s.d));
        // A direction on a cell's edge may be given to its neighbour by rounding, and one next to a pole turns
        // far in longitude: rare.
        if (std::abs(pdf / s.pdf - 1.f) > 1e-3f) ++disagree;
        const float l = e.eval(escaped(s.d)).x / s.pdf;
        if (std::abs(s.weight.x - l) > 1e-3f * l + 1e-6f) ++otherRadiance;
    }
    EXPECT_LT(disagree, n / 1000);
    EXPECT_LT(otherRadiance, n / 1000);
}

TEST(Envmap, ItsEstimateOfTheLightFromEveryDirectionIsTheUniformSpheres) {
    // Importance sampling by the image and uniform sampling of the sphere estimate one integral, E = int L dw;
    // the twin that forgets the Jacobian of the latitude-longitude map (its density 1 / sin(theta) too small near
    // the poles) is rejected by the same test.
    const EnvmapEmitter e(lumpyMap());
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    const int n = 400000;
    double imp = 0, imp2 = 0, uni = 0, uni2 = 0, twin = 0, twin2 = 0;
    for (int i = 0; i < n; ++i) {
        const EmitterSample s = e.sample({}, {u(rng), u(rng)});
        const double w = s.weight.x;
        imp += w;
        imp2 += w * w;
        const Vec3f local = normalize(Transform::rotate({1.f, 0.f, 0.f}, -90.f).vector(s.d));
        const double sinTheta = std::sqrt(double(local.x) * local.x + double(local.z) * local.z);
        const double t = w / std::max(sinTheta, 1e-6);
        twin += t;
        twin2 += t * t;
        const Vec3f d = squareToUniformSphere({u(rng), u(rng)});
        const double v = e.eval(escaped(d)).x / squareToUniformSpherePdf(d);
        uni += v;
        uni2 += v * v;
    }
    const auto se = [n](double s, double s2) { return std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)) / n); };
    const double gap = std::abs(imp / n - uni / n), sigma = std::hypot(se(imp, imp2), se(uni, uni2));
    EXPECT_LT(gap, 4.0 * sigma) << imp / n << " against " << uni / n;
    EXPECT_GT(std::abs(twin / n - uni / n), 4.0 * std::hypot(se(twin, twin2), se(uni, uni2)));
}

namespace {

/// Row values (top, theta = 0, to bottom, theta = pi) and column values (pixel centres at phi = (j + 1/2) 2 pi / W)
/// of a separable image: its bilinear radiance is the product of their linear interpolations.
const std::vector<float> kRows = {0.5f, 4.f, 1.f, 0.2f, 3.f};
const std::vector<float> kColumns = {1.f, 2.f, 3.f, 0.5f, 5.f, 1.f, 0.1f, 2.f};

/// The irradiance E = int L cos(theta) dw over the hemisphere around the image's +y (theta = 0), by quadrature of
/// the interpolated rows and columns: rho / pi E leaves a diffuse plane facing there.
double separableIrradiance() {
    const int steps = 20000;
    const int rows = int(kRows.size()), cols = int(kColumns.size());
    double theta = 0.0, phi = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double t = (i + 0.5) / steps * (kPi / 2), g = t / kPi * (rows - 1);
        const int r = int(g);
        const double a = kRows[r] + (g - r) * (kRows[r + 1] - kRows[r]);
        theta += a * std::cos(t) * std::sin(t) * (kPi / 2) / steps;
    }
    for (int i = 0; i < steps; ++i) {
        double g = (i + 0.5) / steps * cols - 0.5;  // column centres at integers
        if (g < 0) g += cols;
        const int c = int(g);
        const double b = kColumns[c] + (g - c) * (kColumns[(c + 1) % cols] - kColumns[c]);
        phi += b * 2 * kPi / steps;
    }
    return theta * phi;
}

std::string separableExr() {
    std::vector<float> rgb;
    for (float a : kRows)
        for (float b : kColumns) rgb.insert(rgb.end(), {a * b, a * b, a * b});
    return writeExr("separable.exr", int(kColumns.size()), int(kRows.size()), rgb);
}

/// A diffuse plane (reflectance 0.5) at z = 0 facing +z, under an envmap whose +y is turned to +z.
std::string planeScene(const std::string &name, const std::string &integrator, const std::string &envmap) {
    const fs::path path = folder() / (name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n<integrator type=\"" << integrator << "\"/>\n"
                        << "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
                           "<integer name=\"height\" value=\"8\"/></film></sensor>\n"
                           "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"10\"/></transform>"
                           "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf></shape>\n"
                        << envmap << "</scene>\n";
    return path.string();
}

std::string envmapElement(const std::string &file, const std::string &extra = "") {
    return "<emitter type=\"envmap\"><string name=\"filename\" value=\"" + file + "\"/>" +
           "<transform name=\"to_world\"><rotate x=\"1\" angle=\"90\"/></transform>" + extra + "</emitter>\n";
}

}  // namespace

TEST(Envmap, APlaneUnderItShowsTheClosedFormThroughDirectAndPath) {
    const double expected = 0.5 / kPi * separableIrradiance();
    const std::string exr = separableExr();
    for (const char *integrator : {"direct", "path"}) {
        const SceneDescription scene = loadScene(planeScene(std::string("plane_") + integrator, integrator,
                                                            envmapElement(exr)));
        ASSERT_TRUE(scene.envmap.has_value());
        const Estimate got = estimate(scene, {0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}, 100000);
        EXPECT_NEAR(got.mean, expected, 5.0 * got.error + 0.005 * expected) << integrator;
    }
}

TEST(Envmap, TheLoaderRefusesWhatItCannotReadNamingTheLine) {
    const std::string exr = separableExr();
    const auto error = [](const std::string &name, const std::string &envmap, const std::string &integrator = "path") {
        return test::loadError(planeScene(name, integrator, envmap), integrator);
    };
    const auto expectError = [&](const std::string &name, const std::string &envmap, const std::string &words) {
        const std::string e = error(name, envmap);
        EXPECT_NE(e.find(name + ".xml:"), std::string::npos) << e;
        EXPECT_NE(e.find(words), std::string::npos) << e;
    };
    expectError("missing", envmapElement((folder() / "nowhere.exr").string()), "cannot read the envmap's image");
    expectError("png", envmapElement("sky.png"), "OpenEXR");
    expectError("not_exr", envmapElement(test::writeFileIn(folder(), "fake.exr", "not an image")),
                "cannot read the envmap's image");
    expectError("small", envmapElement(writeExr("small.exr", 2, 2, std::vector<float>(12, 1.f))), "2 x 3");
    std::vector<float> negative(4 * 3 * 3, 1.f);
    negative[3 * (4 * 1 + 2)] = -1.f;
    expectError("negative", envmapElement(writeExr("negative.exr", 4, 3, negative)), "pixel (2, 1)");
    expectError("scaled",
                "<emitter type=\"envmap\"><string name=\"filename\" value=\"" + exr +
                    "\"/><transform name=\"to_world\"><scale value=\"2\"/></transform></emitter>\n",
                "rotation");
    expectError("two", envmapElement(exr) + "<emitter type=\"constant\"/>\n", "only one environment emitter");
    // Integrators it does not light skip it, whatever its file.
    EXPECT_EQ(error("skipped", envmapElement("nowhere.exr"), "ao"), "");
    EXPECT_EQ(error("accepted", envmapElement(exr, "<boolean name=\"mis_compensation\" value=\"true\"/>")), "");
}
