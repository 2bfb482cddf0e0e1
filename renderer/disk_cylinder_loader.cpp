#include "disk_cylinder_loader.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "cylinder.h"
#include "disk.h"
#include "scene_limits.h"

namespace mcval {

namespace {

/// Mitsuba's coordinate_system (Duff et al. 2017): a right-handed orthonormal frame (s, t, n) for unit n.
void frameAround(const Vec3d &n, Vec3d &s, Vec3d &t) {
    const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    s = {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x};
    t = {b, sign + n.y * n.y * a, -n.y};
}

/// whyUntraceable for either shape; `what` names it in the message.
template <typename Shape>
std::optional<std::string> untraceable(const Shape &shape, const char *what) {
    if (isDegenerate(shape.toWorld))
        return std::string("the ") + what + "'s to_world is degenerate (a zero scale, or axes that (nearly) "
               "coincide): the shape would have no area";
    Vec3d lo, hi;
    shapeBounds(shape, lo, hi);
    const double extent = std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z), std::abs(hi.x),
                                    std::abs(hi.y), std::abs(hi.z)});  // NaN fails below
    std::ostringstream msg;
    msg << "the " << what << " (after to_world) spans (" << lo.x << ", " << lo.y << ", " << lo.z << ") to (" << hi.x
        << ", " << hi.y << ", " << hi.z << ")";
    if (!(extent <= kMaxCoordinate)) {
        msg << ": it must lie within " << kMaxCoordinate;
        return msg.str();
    }
    // As for the sphere: the size against the largest coordinate of the box's centre.
    const Vec3d c = (lo + hi) * 0.5;
    const double centre = std::max({std::abs(c.x), std::abs(c.y), std::abs(c.z)}), size = shapeSize(shape);
    if (!(size >= kMinSphereRadius && size >= kMinSphereRadiusToCenter * centre)) {
        msg << " with size " << size << ": the size must be at least " << kMinSphereRadius << " and "
            << kMinSphereRadiusToCenter
            << " times its centre's largest coordinate (float32 could not place points on it)";
        return msg.str();
    }
    return std::nullopt;
}

/// Refuses, at to_world, what untraceable() names.
template <typename Shape>
void requireTraceable(XmlProps &props, const Shape &shape) {
    if (const auto why = whyUntraceable(shape)) props.failAt("to_world", *why);
}

}  // namespace

std::optional<std::string> whyUntraceable(const Disk &disk) { return untraceable(disk, "disk"); }

std::optional<std::string> whyUntraceable(const Cylinder &cyl) { return untraceable(cyl, "cylinder"); }

Disk loadDisk(XmlProps &props, const Transform &toWorld) {
    Disk disk;
    disk.flipNormals = props.getBool("flip_normals", false);
    props.finish("flip_normals, to_world");
    disk.toWorld = Affine::from(toWorld);
    requireTraceable(props, disk);
    return disk;
}

Cylinder loadCylinder(XmlProps &props, const Transform &toWorld) {
    const Vec3d p0(props.getPoint("p0", {0.f, 0.f, 0.f})), p1(props.getPoint("p1", {0.f, 0.f, 1.f}));
    const float radius = props.getFloat("radius", 1.f);
    Cylinder cyl;
    cyl.flipNormals = props.getBool("flip_normals", false);
    props.finish("p0, p1, radius, flip_normals, to_world");
    if (!(radius > 0.f)) {
        std::ostringstream msg;
        msg << "radius must be positive, got " << radius;
        props.failAt("radius", msg.str());
    }
    const Vec3d axis = p1 - p0;
    const double length = norm(axis);
    if (!(length > 0.0)) props.failAt("p1", "p1 must differ from p0 (the cylinder's axis runs from p0 to p1)");
    // Object space is the unit cylinder: scale it to (radius, length), turn +z onto p1 - p0, move it to p0.
    Vec3d s, t;
    const Vec3d n = axis * (1.0 / length);
    frameAround(n, s, t);
    const Affine local = Affine::fromColumns(s * radius, t * radius, n * length, p0);
    cyl.toWorld = Affine::from(toWorld) * local;
    requireTraceable(props, cyl);
    return cyl;
}

}  // namespace mcval
