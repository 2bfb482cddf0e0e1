// Spawned rays leave their surface by an offset that scales with the scene: the same scene at a
// millimetre, metre or kilometre scale renders the same image (contact shadows do not vanish).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "ray.h"
#include "render.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

/// An exact sphere of radius s resting on a floor 20 s wide, seen and lit as at unit scale: lengths
/// times s, the point light's intensity times s^2 (so its irradiance is the same).
std::string sphereOnFloor(double s) {
    std::ostringstream x;
    x << "<scene version=\"3.0.0\">\n<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/>"
      << "<float name=\"near_clip\" value=\"" << 0.01 * s << "\"/><float name=\"far_clip\" value=\"" << 1e4 * s
      << "\"/><transform name=\"to_world\"><lookat origin=\"0, " << 2 * s << ", " << 4.8 * s << "\" target=\""
      << -0.3 * s << ", " << 0.7 * s << ", 0\" up=\"0, 1, 0\"/></transform><film type=\"hdrfilm\">"
      << "<integer name=\"width\" value=\"32\"/><integer name=\"height\" value=\"32\"/></film></sensor>\n"
      << "<shape type=\"rectangle\"><transform name=\"to_world\"><scale value=\"" << 10 * s
      << "\"/><rotate x=\"1\" angle=\"-90\"/></transform></shape>\n"
      << "<shape type=\"sphere\"><point name=\"center\" value=\"0, " << s << ", 0\"/><float name=\"radius\" value=\""
      << s << "\"/></shape>\n<emitter type=\"point\"><point name=\"position\" value=\"" << 3 * s << ", " << 5 * s
      << ", " << 2 * s << "\"/><rgb name=\"intensity\" value=\"" << 80 * s * s << "\"/></emitter>\n"
      << "<emitter type=\"constant\"/>\n</scene>\n";
    const fs::path path = fs::temp_directory_path() / ("mcval_offset_scale_" + std::to_string(s) + ".xml");
    std::ofstream(path) << x.str();
    return path.string();
}

double imageMean(double scale, const char *integrator) {
    RenderOptions options;
    options.spp = 16;
    options.seed = 3;
    options.integrator = integrator;
    const RenderOutput out = render(loadScene(sphereOnFloor(scale)), options);
    double sum = 0.0;
    for (float v : out.mean.rgb) sum += v;
    return sum / double(out.mean.rgb.size());
}

}  // namespace

TEST(RayOffset, TheSameSceneAtEveryScaleGivesTheSameImage) {
    for (const char *integrator : {"simple", "ao"}) {
        const double unit = imageMean(1.0, integrator);
        ASSERT_GT(unit, 0.0);
        for (const double scale : {1e-3, 1e3}) EXPECT_NEAR(imageMean(scale, integrator), unit, 1e-4 * unit)
            << integrator << " at scale " << scale;
    }
}

TEST(RayOffset, TheFloorMovesEveryCoordinateAndUlpsTakeOverFarOut) {
    const float floor = 1.8e-7f;  // a millimetre scene's floor
    const Vec3f n = normalize(Vec3f(1.f, 1.f, 1.f));
    const Vec3f moved = offsetRayOrigin(Vec3f(1e-3f, 0.f, -1e-3f), n, floor);
    EXPECT_NEAR(moved.x - 1e-3f, floor * n.x, 1e-10f);
    EXPECT_NEAR(moved.y, floor * n.y, 1e-12f);  // at 0 a fixed absolute step would be far too large
    EXPECT_GT(moved.z, -1e-3f);
    // At 0 (and -0) toward either side the result is finite: stepping the bits of 0 down would be a NaN.
    for (const float zero : {0.f, -0.f}) {
        const Vec3f down = offsetRayOrigin(Vec3f(zero, zero, zero), Vec3f(0.f, -1.f, 0.f), floor);
        EXPECT_TRUE(std::isfinite(down.x) && std::isfinite(down.y) && std::isfinite(down.z));
        EXPECT_FLOAT_EQ(down.y, -floor);
    }
    // Far from the origin the ulps of the coordinate dominate: still off the surface.
    const Vec3f far = offsetRayOrigin(Vec3f(1e5f, 0.f, 0.f), Vec3f(1.f, 0.f, 0.f), floor);
    EXPECT_GE(far.x - 1e5f, 256.f * (std::nextafter(1e5f, 1e6f) - 1e5f) * 0.99f);
}
