#include "cylinder.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mcval {

bool intersectShape(const Cylinder &cyl, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t) {
    // Object space keeps the ray's parameter: o' + t d' is the image of o + t d.
    const Vec3d lo = cyl.toWorld.inversePoint(Vec3d(o)), ld = cyl.toWorld.inverseVector(Vec3d(d));
    // x^2 + y^2 = 1 in the xy plane: a t^2 + b t + c = 0.
    const double a = ld.x * ld.x + ld.y * ld.y, b = 2.0 * (ld.x * lo.x + ld.y * lo.y);
    if (!(a > 0.0)) return false;  // along the axis: no hit (as Mitsuba), or not finite
    // The discriminant from the ray's closest approach to the axis, and c as a product, as the sphere
    // does: b^2 - 4ac and x^2 + y^2 - 1 cancel catastrophically for far or grazing rays.
    const double k = b / (2.0 * a);
    const double vx = lo.x - k * ld.x, vy = lo.y - k * ld.y;
    const double closest = std::sqrt(vx * vx + vy * vy);
    const double disc = 4.0 * a * (1.0 + closest) * (1.0 - closest);
    if (!(disc >= 0.0)) return false;
    const double root = std::sqrt(disc);
    const double q = b < 0.0 ? -0.5 * (b - root) : -0.5 * (b + root);
    if (q == 0.0) return false;  // the origin on the surface, the ray tangent to it
    const double dist = std::sqrt(lo.x * lo.x + lo.y * lo.y);
    double t0 = q / a, t1 = (dist - 1.0) * (dist + 1.0) / q;
    if (t0 > t1) std::swap(t0, t1);
    // The nearer root within the ray's span and the cylinder's length, else the farther.
    for (const double candidate : {t0, t1}) {
        const double z = lo.z + candidate * ld.z;
        if (candidate >= tnear && candidate <= tfar && z >= 0.0 && z <= 1.0) {
            t = candidate;
            return true;
        }
    }
    return false;
}

void shapeHitPoint(const Cylinder &cyl, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n) {
    const Vec3d local = cyl.toWorld.inversePoint(Vec3d(o)) + cyl.toWorld.inverseVector(Vec3d(d)) * t;
    const double r = std::hypot(local.x, local.y);
    const double cx = r > 0.0 ? local.x / r : 1.0, cy = r > 0.0 ? local.y / r : 0.0;
    p = cyl.toWorld.point({cx, cy, local.z}).toFloat();
    // Mitsuba's normal, cross(dp/du, dp/dv) under to_world, flipped once more where to_world mirrors
    // (its decomposition's negative scale): the inverse transpose of the radial direction, outward.
    const double sign = cyl.flipNormals ? -1.0 : 1.0;
    const Vec3d m = cyl.toWorld.normal({sign * cx, sign * cy, 0.0});
    n = (m * (1.0 / norm(m))).toFloat();
}

void shapeBounds(const Cylinder &cyl, Vec3d &lo, Vec3d &hi) {
    const Affine &f = cyl.toWorld;
    const Vec3d u = f.column(0), v = f.column(1), c0 = f.b, c1 = f.b + f.column(2);
    const Vec3d e{std::hypot(u.x, v.x), std::hypot(u.y, v.y), std::hypot(u.z, v.z)};
    lo = {std::min(c0.x, c1.x) - e.x, std::min(c0.y, c1.y) - e.y, std::min(c0.z, c1.z) - e.z};
    hi = {std::max(c0.x, c1.x) + e.x, std::max(c0.y, c1.y) + e.y, std::max(c0.z, c1.z) + e.z};
}

double shapeSize(const Cylinder &cyl) {
    const Affine &f = cyl.toWorld;
    return std::min({norm(f.column(0)), norm(f.column(1)), norm(f.column(2))});
}

}  // namespace mcval
