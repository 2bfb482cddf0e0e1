#include "disk.h"

#include <algorithm>
#include <cmath>

namespace mcval {

namespace {
/// The hit's object-space point, from the ray mapped to object space.
Vec3d localPoint(const Disk &disk, const Vec3f &o, const Vec3f &d, double t) {
    const Vec3d lo = disk.toWorld.inversePoint(Vec3d(o)), ld = disk.toWorld.inverseVector(Vec3d(d));
    return lo + ld * t;
}
}  // namespace

bool intersectShape(const Disk &disk, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t) {
    // Object space keeps the ray's parameter: o' + t d' is the image of o + t d.
    const Vec3d lo = disk.toWorld.inversePoint(Vec3d(o)), ld = disk.toWorld.inverseVector(Vec3d(d));
    if (ld.z == 0.0) return false;  // parallel to the disk's plane
    const double hit = -lo.z / ld.z;
    const double x = lo.x + hit * ld.x, y = lo.y + hit * ld.y;
    if (!(hit >= tnear && hit <= tfar && x * x + y * y <= 1.0)) return false;  // NaN fails too
    t = hit;
    return true;
}

void shapeHitPoint(const Disk &disk, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n) {
    const Vec3d local = localPoint(disk, o, d, t);
    p = disk.toWorld.point({local.x, local.y, 0.0}).toFloat();
    const Vec3d m = disk.toWorld.normal({0.0, 0.0, disk.flipNormals ? -1.0 : 1.0});
    n = (m * (1.0 / norm(m))).toFloat();
}

void shapeBounds(const Disk &disk, Vec3d &lo, Vec3d &hi) {
    const Affine &f = disk.toWorld;
    // The ellipse c + u cos(phi) + v sin(phi) reaches c_i +- sqrt(u_i^2 + v_i^2) along axis i.
    const Vec3d u = f.column(0), v = f.column(1);
    const Vec3d e{std::hypot(u.x, v.x), std::hypot(u.y, v.y), std::hypot(u.z, v.z)};
    lo = f.b - e;
    hi = f.b + e;
}

double shapeSize(const Disk &disk) {
    const Vec3d u = disk.toWorld.column(0), v = disk.toWorld.column(1);
    // The semi-axes a >= b of the ellipse have a b = |u x v| and a / sqrt 2 <= max(|u|, |v|) <= a.
    const double area = norm(cross(u, v)), longer = std::max(norm(u), norm(v));
    return longer > 0.0 ? area / longer : 0.0;
}

}  // namespace mcval
