#include "sphere_loader.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "scene_limits.h"

namespace mcval {

namespace {

/// The uniform scale s of a similarity's linear part (columns orthogonal, of one length s), or 0 if
/// it shears or scales unevenly beyond float32 rounding.
double similarityScale(const Transform &t) {
    double gram[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            gram[i][j] = 0.0;
            for (int k = 0; k < 3; ++k) gram[i][j] += double(t.m[k][i]) * t.m[k][j];
        }
    const double s2 = (gram[0][0] + gram[1][1] + gram[2][2]) / 3.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (!(std::abs(gram[i][j] - (i == j ? s2 : 0.0)) <= 1e-5 * s2)) return 0.0;
    return std::sqrt(s2);
}

}  // namespace

Sphere loadSphere(XmlProps &props, const Transform &toWorld) {
    Sphere local;
    local.center = props.getPoint("center", {0.f, 0.f, 0.f});
    local.radius = props.getFloat("radius", 1.f);
    local.flipNormals = props.getBool("flip_normals", false);
    props.finish("center, radius, flip_normals, to_world");
    if (!(local.radius > 0.f)) {
        std::ostringstream msg;
        msg << "radius must be positive, got " << local.radius;
        props.failAt("radius", msg.str());
    }
    Sphere sphere;
    if (const auto refusal = placeSphere(local, toWorld, true, sphere))
        props.failAt(refusal->property, refusal->reason);
    return sphere;
}

std::optional<SphereRefusal> placeSphere(const Sphere &local, const Transform &toWorld, bool ownTransform,
                                         Sphere &out) {
    const double scale = similarityScale(toWorld);
    if (scale == 0.0)
        return SphereRefusal{"to_world", "a sphere's to_world may only translate, rotate and scale uniformly: "
                                         "this one shears or scales unevenly (Mitsuba would keep a sphere anyway; "
                                         "use a mesh)"};
    Sphere sphere = local;
    sphere.center = toWorld.point(local.center);
    const double r = scale * local.radius;
    sphere.radius = float(r);
    sphere.flipNormals = local.flipNormals != (ownTransform && toWorld.determinant3() < 0.f);
    const Vec3f &c = sphere.center;
    const double extent = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}) + r;  // NaN fails below
    std::ostringstream msg;
    msg << "the sphere (after to_world) has centre (" << c.x << ", " << c.y << ", " << c.z << ") and radius " << r;
    if (!(extent <= kMaxCoordinate))
        return SphereRefusal{"to_world", msg.str() + ": it must lie within " + std::to_string(kMaxCoordinate)};
    if (!(r >= kMinSphereRadius && r >= kMinSphereRadiusToCenter * (extent - r))) {
        msg << ": the radius must be at least " << kMinSphereRadius << " and " << kMinSphereRadiusToCenter
            << " times the centre's largest coordinate (float32 could not place points on it)";
        return SphereRefusal{"radius", msg.str()};
    }
    out = sphere;
    return std::nullopt;
}

}  // namespace mcval
