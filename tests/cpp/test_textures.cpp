// Textured reflectances and masks: a bitmap's value at (u, v) is Mitsuba 3's (values Mitsuba 3.9.1's scalar_rgb
// bitmap gives for the same 8-bit PNG, to_uv, wrap mode and filter), a checkerboard's too; a textured plane under a
// uniform sky shows the texture's value where the camera ray meets it, through an OBJ's texture coordinates (v upside
// down, as Mitsuba reads them) and a rectangle's; a mask shows its surface and the sky through its holes in
// proportion to its opacity; and the loader refuses, naming the line, what it does not model.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "error.h"
#include "load_error.h"
#include "radiance_estimate.h"
#include "temp_files.h"
#include "bsdfs/masked.h"
#include "textures/texture_loader.h"
#include "warp.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

constexpr const char *kPrefix = "mcval_textures_";
fs::path folder() { return test::tempFolder(kPrefix); }
const auto *const kCleanup =
    ::testing::AddGlobalTestEnvironment(new test::TempFolderCleanup(test::tempFolderPath(kPrefix)));

/// An image file in the test's folder, written by OpenImageIO (its format from the name's extension).
std::string writeImage(const std::string &name, int width, int height, OIIO::TypeDesc type, const void *pixels) {
    const std::string path = (folder() / name).string();
    auto out = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(out && out->open(path, OIIO::ImageSpec(width, height, 3, type)));
    if (out) {
        out->write_image(type, pixels);
        out->close();
    }
    return path;
}

/// The 4 x 3 8-bit RGB PNG the Mitsuba values were taken of: pixel (x, y) = (20 + 60x, 30 + 100y, 37 (x + 3y) mod 256).
std::string probePng() {
    std::vector<unsigned char> px;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x)
            px.insert(px.end(), {(unsigned char)(20 + 60 * x), (unsigned char)(30 + 100 * y),
                                 (unsigned char)((37 * (x + 3 * y)) % 256)});
    return writeImage("probe.png", 4, 3, OIIO::TypeDesc::UINT8, px.data());
}

void expectColor(const Color &got, const Color &want, const std::string &what) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR((&got.x)[k], (&want.x)[k], 2e-3f * (&want.x)[k] + 2e-4f) << what << " " << k;
}

}  // namespace

TEST(Textures, ABitmapIsMitsubasLookupForEveryWrapAndFilter) {
    const auto image = std::make_shared<const RgbImage>(readRgbImage(probePng(), false));
    const UvTransform toUv(Transform::translate({0.1f, 0.05f, 0.f}) * Transform::scale({1.5f, 1.25f, 1.f}));
    const Vec2f uvs[5] = {{0.1f, 0.2f}, {0.5f, 0.5f}, {0.9f, 0.95f}, {-0.3f, 1.4f}, {1.7f, -0.6f}};
    struct Case {
        WrapMode wrap;
        FilterMode filter;
        Color want[5];
    };
    const Case cases[] = {
        {WrapMode::Repeat, FilterMode::Bilinear,
         {{0.043608f, 0.097081f, 0.09657f}, {0.546048f, 0.521465f, 0.371496f}, {0.134829f, 0.05766f, 0.101355f},
          {0.293784f, 0.734491f, 0.074835f}, {0.293784f, 0.097081f, 0.250388f}}},
        {WrapMode::Repeat, FilterMode::Nearest,
         {{0.08022f, 0.012983f, 0.0185f}, {0.577581f, 0.791298f, 0.074214f}, {0.08022f, 0.012983f, 0.0185f},
          {0.262251f, 0.791298f, 0.021219f}, {0.262251f, 0.012983f, 0.068478f}}},
        {WrapMode::Mirror, FilterMode::Bilinear,
         {{0.043608f, 0.097081f, 0.09657f}, {0.546048f, 0.521465f, 0.371496f}, {0.207641f, 0.670583f, 0.102957f},
          {0.072897f, 0.034008f, 0.043227f}, {0.293784f, 0.56407f, 0.219784f}}},
        {WrapMode::Mirror, FilterMode::Nearest,
         {{0.08022f, 0.012983f, 0.0185f}, {0.577581f, 0.791298f, 0.074214f}, {0.262251f, 0.791298f, 0.021219f},
          {0.08022f, 0.012983f, 0.0185f}, {0.262251f, 0.791298f, 0.021219f}}},
        {WrapMode::Clamp, FilterMode::Bilinear,
         {{0.043608f, 0.097081f, 0.09657f}, {0.546048f, 0.521465f, 0.371496f}, {0.577581f, 0.791298f, 0.074214f},
          {0.006995f, 0.791298f, 0.730461f}, {0.577581f, 0.012983f, 0.158961f}}},
        {WrapMode::Clamp, FilterMode::Nearest,
         {{0.08022f, 0.012983f, 0.0185f}, {0.577581f, 0.791298f, 0.074214f}, {0.577581f, 0.791298f, 0.074214f},
          {0.006995f, 0.791298f, 0.730461f}, {0.577581f, 0.012983f, 0.158961f}}},
    };
    for (const Case &c : cases) {
        const BitmapTexture texture(image, c.wrap, c.filter, toUv);
        for (int i = 0; i < 5; ++i)
            expectColor(texture.eval(uvs[i]), c.want[i],
                        "wrap " + std::to_string(int(c.wrap)) + " filter " + std::to_string(int(c.filter)) + " uv " +
                            std::to_string(i));
    }
}

TEST(Textures, ACheckerboardIsMitsubas) {
    const CheckerboardTexture texture({0.4f, 0.4f, 0.4f}, {0.2f, 0.2f, 0.2f}, UvTransform(Transform::scale({3.f, 2.f, 1.f})));
    const float want[5] = {0.4f, 0.4f, 0.4f, 0.2f, 0.2f};
    const Vec2f uvs[5] = {{0.1f, 0.2f}, {0.5f, 0.5f}, {0.9f, 0.95f}, {-0.3f, 1.4f}, {1.7f, -0.6f}};
    for (int i = 0; i < 5; ++i) EXPECT_EQ(texture.eval(uvs[i]).y, want[i]) << i;
}

namespace {

/// A 2 x 2 checkerboard image, linear (an OpenEXR): (0.1, 0.2, 0.3) (0.9, 0.8, 0.7) on the top row, the other
/// way round below.
std::string checkerExr() {
    const std::vector<float> px = {0.1f, 0.2f, 0.3f, 0.9f, 0.8f, 0.7f, 0.9f, 0.8f, 0.7f, 0.1f, 0.2f, 0.3f};
    return writeImage("checker.exr", 2, 2, OIIO::TypeDesc::FLOAT, px.data());
}

/// A unit square at z = 0 facing +z as an OBJ with texture coordinates: its corner (x, y) at (u, v) = (x, y).
std::string squareObj() {
    return test::writeFileIn(folder(), "square.obj",
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
}

std::string scene(const std::string &name, const std::string &integrator, const std::string &shape) {
    const fs::path path = folder() / (name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n<integrator type=\"" << integrator << "\"/>\n"
                        << "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"8\"/>"
                           "<integer name=\"height\" value=\"8\"/></film></sensor>\n"
                           "<emitter type=\"constant\"/>\n<emitter type=\"point\"/>\n"
                        << shape << "</scene>\n";
    return path.string();
}

std::string texturedBsdf(const std::string &texture) {
    return "<bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"bitmap\"><string name=\"filename\" value=\"" +
           texture + "\"/><string name=\"filter_type\" value=\"nearest\"/></texture></bsdf>";
}

}  // namespace

TEST(Textures, APlaneShowsItsTexturesValueWhereTheRayMeetsIt) {
    // Under a sky of radiance 1, a diffuse surface of albedo rho leaves rho toward every direction: the pixel of
    // the texture at the point's (u, v). The OBJ's v = 0.25 is Mitsuba's 0.75: the bottom row of the image.
    const std::string exr = checkerExr();
    const std::string obj = "<shape type=\"obj\"><string name=\"filename\" value=\"" + squareObj() + "\"/>" +
                            texturedBsdf(exr) + "</shape>\n";
    for (const char *integrator : {"direct", "path"}) {
        const SceneDescription s = loadScene(scene(std::string("obj_") + integrator, integrator, obj));
        EXPECT_NEAR(estimate(s, {0.25f, 0.25f, 1.f}, {0.f, 0.f, -1.f}, 4000).mean, 0.9, 0.02) << integrator;
        EXPECT_NEAR(estimate(s, {0.75f, 0.25f, 1.f}, {0.f, 0.f, -1.f}, 4000).mean, 0.1, 0.005) << integrator;
        EXPECT_NEAR(estimate(s, {0.25f, 0.75f, 1.f}, {0.f, 0.f, -1.f}, 4000).mean, 0.1, 0.005) << integrator;
    }
    // A rectangle's (u, v) = ((x + 1) / 2, (y + 1) / 2), not turned upside down.
    const std::string rectangle = "<shape type=\"rectangle\">" + texturedBsdf(exr) + "</shape>\n";
    const SceneDescription s = loadScene(scene("rectangle", "direct", rectangle));
    EXPECT_NEAR(estimate(s, {-0.5f, -0.5f, 1.f}, {0.f, 0.f, -1.f}, 4000).mean, 0.1, 0.005);
    EXPECT_NEAR(estimate(s, {0.5f, -0.5f, 1.f}, {0.f, 0.f, -1.f}, 4000).mean, 0.9, 0.02);
}

TEST(Textures, TheLoaderRefusesWhatItDoesNotModelNamingTheLine) {
    const std::string exr = checkerExr();
    const auto expectError = [](const std::string &path, const std::string &integrator, const std::string &words) {
        const std::string e = test::loadError(path, integrator);
        EXPECT_NE(e.find(fs::path(path).filename().string() + ":"), std::string::npos) << e;
        EXPECT_NE(e.find(words), std::string::npos) << e;
    };
    const std::string rectangle = "<shape type=\"rectangle\">" + texturedBsdf(exr) + "</shape>\n";
    // One albedo per surface: simple refuses it; ao reads no material and skips it.
    expectError(scene("simple", "simple", rectangle), "simple", "reflectance");
    EXPECT_EQ(test::loadError(scene("ao", "ao", rectangle), "ao"), "");
    EXPECT_EQ(test::loadError(scene("ao_missing", "ao", "<shape type=\"rectangle\">" +
                                                             texturedBsdf("nowhere.png") + "</shape>\n"),
                              "ao"),
              "");
    expectError(scene("sphere", "path", "<shape type=\"sphere\">" + texturedBsdf(exr) + "</shape>\n"), "path",
                "texture coordinates");
    expectError(scene("twosided", "path", "<shape type=\"rectangle\"><bsdf type=\"twosided\">" + texturedBsdf(exr) +
                                              "</bsdf></shape>\n"),
                "path", "twosided");
    expectError(scene("missing", "path", "<shape type=\"rectangle\">" + texturedBsdf("nowhere.png") + "</shape>\n"),
                "path", "cannot read the texture's image");
    expectError(scene("wrap", "path",
                      "<shape type=\"rectangle\"><bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"bitmap\">"
                      "<string name=\"filename\" value=\"" + exr + "\"/><string name=\"wrap_mode\" value=\"tile\"/>"
                      "</texture></bsdf></shape>\n"),
                "path", "expected repeat, mirror or clamp");
    const std::vector<float> twos(2 * 2 * 3, 2.f);
    const std::string bright = writeImage("bright.exr", 2, 2, OIIO::TypeDesc::FLOAT, twos.data());
    expectError(scene("bright", "path", "<shape type=\"rectangle\">" + texturedBsdf(bright) + "</shape>\n"), "path",
                "outside [0, 1");
}

TEST(Textures, AMaskIsItsSurfaceWhereOpaqueAndAHoleElsewhere) {
    // A plane of opacity alpha over diffuse rho under a sky of radiance 1, nothing behind it: a camera ray sees
    // alpha rho (the surface) + (1 - alpha) (the sky through the hole), through direct and path alike.
    const std::string masked = "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"10\"/></transform>"
                               "<bsdf type=\"mask\"><float name=\"opacity\" value=\"0.3\"/><bsdf type=\"diffuse\">"
                               "<rgb name=\"reflectance\" value=\"0.6\"/></bsdf></bsdf></shape>\n";
    for (const char *integrator : {"direct", "path"}) {
        const SceneDescription s = loadScene(scene(std::string("mask_") + integrator, integrator, masked));
        const Estimate got = estimate(s, {0.3f, 0.2f, 1.f}, {0.f, 0.f, -1.f}, 40000);
        EXPECT_NEAR(got.mean, 0.3 * 0.6 + 0.7, 5.0 * got.error + 1e-3) << integrator;
    }
    // Its samples: the nested one's with alpha times its density (its weight unchanged), or straight on.
    const DiffuseBsdf diffuse({0.6f, 0.6f, 0.6f});
    const MaskedBsdf mask(0.3f, &diffuse);
    const Vec3f wi = normalize(Vec3f(0.3f, 0.1f, 0.9f));
    const BsdfSample surface = mask.sample(wi, {0.4f, 0.7f}, 0.2f);
    EXPECT_NEAR(surface.pdf, 0.3f * diffuse.pdf(wi, surface.wo), 1e-6f);
    EXPECT_NEAR(surface.pdf, mask.pdf(wi, surface.wo), 1e-6f);
    EXPECT_NEAR(surface.weight.x, mask.eval(wi, surface.wo).x / surface.pdf, 1e-5f);
    const BsdfSample hole = mask.sample(wi, {0.4f, 0.7f}, 0.5f);
    EXPECT_TRUE(std::isinf(hole.pdf));
    EXPECT_EQ(hole.wo.z, -wi.z);
    EXPECT_EQ(hole.weight.y, 1.f);
}

TEST(Textures, AMaskTheLoaderCannotReadIsRefused) {
    const auto mask = [](const std::string &inside) {
        return "<shape type=\"rectangle\"><bsdf type=\"mask\">" + inside + "</bsdf></shape>\n";
    };
    const std::string diffuse = "<bsdf type=\"diffuse\"/>";
    const auto expectError = [](const std::string &path, const std::string &integrator, const std::string &words) {
        const std::string e = test::loadError(path, integrator);
        EXPECT_NE(e.find(fs::path(path).filename().string() + ":"), std::string::npos) << e;
        EXPECT_NE(e.find(words), std::string::npos) << e;
    };
    expectError(scene("mask_simple", "simple", mask(diffuse)), "simple", "diffuse surfaces only");
    EXPECT_EQ(test::loadError(scene("mask_ao", "ao", mask("<texture name=\"opacity\" type=\"bitmap\"><string "
                                                          "name=\"filename\" value=\"nowhere.png\"/></texture>" +
                                                          diffuse)),
                              "ao"),
              "");
    expectError(scene("mask_empty", "path", mask("")), "path", "nested");
    expectError(scene("mask_mask", "path", mask("<bsdf type=\"mask\">" + diffuse + "</bsdf>")), "path",
                "a mask inside a mask");
    expectError(scene("mask_opacity", "path", mask("<float name=\"opacity\" value=\"1.5\"/>" + diffuse)), "path",
                "opacity");
}

TEST(Textures, ASpotsProjectedImageScalesItsIntensity) {
    // A spot 1 above a diffuse plane, pointing down: a uniform image of 0.5 halves the light on the axis; a
    // checkerboard projects its squares (uv = 1/2 + (x, y) / (2 z tan(cutoff)): the axis at uv (1/2, 1/2)).
    const auto spot = [](const std::string &texture) {
        return "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"10\"/></transform>"
               "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"1\"/></bsdf></shape>\n"
               "<emitter type=\"spot\"><rgb name=\"intensity\" value=\"2\"/>" + texture +
               "<transform name=\"to_world\"><lookat origin=\"0, 0, 1\" target=\"0, 0, 0\" up=\"0, 1, 0\"/>"
               "</transform></emitter>\n";
    };
    const auto radiance = [&](const std::string &name, const std::string &texture, const Vec3f &at) {
        const std::string path = (folder() / (name + ".xml")).string();
        std::ofstream(path) << "<scene version=\"3.0.0\">\n<integrator type=\"direct\"/>\n<sensor type=\"perspective\">"
                               "<film type=\"hdrfilm\"/></sensor>\n" << spot(texture) << "</scene>\n";
        return estimate(loadScene(path), {at.x, at.y, 1.f}, {0.f, 0.f, -1.f}, 16).mean;
    };
    const double plain = radiance("spot_plain", "", {0.f, 0.f, 0.f});
    EXPECT_NEAR(plain, 2.0 / kPi, 1e-4);  // rho / pi * I / d^2
    const std::string half = "<texture name=\"texture\" type=\"checkerboard\"><float name=\"color0\" value=\"0.5\"/>"
                             "<float name=\"color1\" value=\"0.5\"/></texture>";
    EXPECT_NEAR(radiance("spot_half", half, {0.f, 0.f, 0.f}), 0.5 * plain, 1e-5);
    const std::string checks = "<texture name=\"texture\" type=\"checkerboard\"><float name=\"color0\" value=\"1\"/>"
                               "<float name=\"color1\" value=\"0.25\"/></texture>";
    // Off the axis by a tenth of the cone's radius at the plane: u or v moves from 1/2 by 1/20.
    const float r = 0.1f * std::tan(20.f * kPi / 180.f);
    const double a = radiance("spot_a", checks, {r, r, 0.f}), b = radiance("spot_b", checks, {r, -r, 0.f});
    EXPECT_NEAR(std::max(a, b) / std::min(a, b), 4.0, 1e-3);
}
