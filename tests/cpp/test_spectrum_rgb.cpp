// Per-wavelength spectra to RGB as Mitsuba 3's RGB variants load them: the expected colours are Mitsuba 3.9.1's
// own (mi.spectrum_list_to_srgb with bounded and d65 as its loader sets them: both for a reflectance, neither for
// light), to within 1e-5 relative; and a scene file's spectrum reaches its material and its emitter so.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "error.h"
#include "load_error.h"
#include "render.h"
#include "scene.h"
#include "spectrum_rgb.h"

using namespace mcval;

namespace {

struct Case {
    std::vector<float> wavelengths, values;
    SpectrumUse use;
    Vec3f mitsuba;
};

void expectNear(const Vec3f &got, const Vec3f &want, const std::string &what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], 1e-5f * std::max(1.f, std::abs(want[c]))) << what << " channel " << c;
}

}  // namespace

TEST(SpectrumRgb, MatchesMitsubasConversion) {
    const Case cases[] = {
        {{400, 500, 600, 700}, {0.78f, 0.78f, 0.78f, 0.78f}, SpectrumUse::Reflectance,
         {0.776367723941803f, 0.7798091173171997f, 0.7760289311408997f}},
        {{400, 500, 600, 700}, {0, 8, 15.6f, 18.4f}, SpectrumUse::Emission,
         {20.7108211517334f, 10.854641914367676f, 2.771151065826416f}},
        {{400, 700}, {1, 2}, SpectrumUse::Emission, {2.1400043964385986f, 1.4042383432388306f, 1.0171406269073486f}},
        {{380, 450, 520, 610, 690, 780}, {0.05f, 0.9f, 0.2f, 0.7f, 0.1f, 0.95f}, SpectrumUse::Reflectance,
         {0.6801679730415344f, 0.3343508541584015f, 0.7495961785316467f}},
        // Beyond the CIE range on both sides; a step; out of gamut (clamped: below 0, and above 1 as a reflectance).
        {{300, 900}, {1, 1}, SpectrumUse::Reflectance, {0.9989834427833557f, 0.9988722801208496f, 0.9988021850585938f}},
        {{350, 550, 551, 900}, {0, 0, 3, 3}, SpectrumUse::Emission, {4.725046634674072f, 1.056368112564087f, 0.f}},
        {{580, 600, 620, 640}, {1, 1, 1, 1}, SpectrumUse::Reflectance, {1.f, 0.05459724739193916f, 0.f}},
        {{580, 600, 620, 640}, {1, 1, 1, 1}, SpectrumUse::Emission, {1.1671792268753052f, 0.05720290169119835f, 0.f}},
    };
    int i = 0;
    for (const Case &c : cases)
        expectNear(spectrumToRgb(c.wavelengths, c.values, c.use), c.mitsuba, "case " + std::to_string(i++));
}

TEST(SpectrumRgb, AScenesSpectraAreReadAsReflectanceOrAsLight) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() / "mcval_spectrum_scene.xml";
    const auto write = [&](const std::string &spectrum) {
        std::ofstream(path) << "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"><film type=\"hdrfilm\"><integer "
                               "name=\"width\" value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n"
                               "  <shape type=\"rectangle\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" "
                               "value=\"400:0.78, 500:0.78, 600:0.78, 700:0.78\"/></bsdf>\n"
                               "  <emitter type=\"area\">" << spectrum << "</emitter></shape>\n</scene>\n";
    };
    write("<spectrum name=\"radiance\" value=\"400:0, 500:8, 600:15.6, 700:18.4\"/>");
    const SceneDescription scene = loadScene(path.string(), {}, "path");
    const Mesh &mesh = scene.meshes.at(0);
    expectNear(*scene.bsdfs.at(mesh.bsdf)->lambertianAlbedo(true),
               {0.776367723941803f, 0.7798091173171997f, 0.7760289311408997f}, "reflectance");
    ASSERT_TRUE(mesh.areaRadiance.has_value());
    expectNear(*mesh.areaRadiance, {20.7108211517334f, 10.854641914367676f, 2.771151065826416f}, "radiance");
    // Malformed: the error names the line.
    write("\n    <spectrum name=\"radiance\" value=\"500:1, 400:2\"/>");
    EXPECT_NE(test::loadError(path.string(), "path").find(":5:"), std::string::npos);
    write("\n    <spectrum name=\"radiance\" value=\"500:1\"/>");
    EXPECT_NE(test::loadError(path.string(), "path").find("at least two"), std::string::npos);
    write("\n    <spectrum name=\"radiance\" filename=\"light.spd\"/>");
    EXPECT_NE(test::loadError(path.string(), "path").find("read from a file"), std::string::npos);
}
