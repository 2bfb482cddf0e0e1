#include "sphere.h"

#include <cmath>
#include <limits>
#include <utility>

namespace mcval {

namespace {

struct Vec3d {
    double x, y, z;
};
double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec3d toDouble(const Vec3f &v) { return {v.x, v.y, v.z}; }

}  // namespace

bool intersectSphere(const Sphere &sphere, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t) {
    const Vec3d dd = toDouble(d);
    const Vec3d oc{double(o.x) - sphere.center.x, double(o.y) - sphere.center.y, double(o.z) - sphere.center.z};
    const double r = sphere.radius;
    const double a = dot(dd, dd), b = 2.0 * dot(dd, oc);
    if (!(a > 0.0)) return false;
    // The discriminant from the ray's closest approach to the centre, and the constant term as a
    // product: b^2 - 4ac and |oc|^2 - r^2 cancel catastrophically for far or grazing rays (pbrt-v4).
    const double k = b / (2.0 * a);
    const Vec3d v{oc.x - k * dd.x, oc.y - k * dd.y, oc.z - k * dd.z};
    const double closest = std::sqrt(dot(v, v));
    const double disc = 4.0 * a * (r + closest) * (r - closest);
    if (!(disc >= 0.0)) return false;
    const double root = std::sqrt(disc);
    const double q = b < 0.0 ? -0.5 * (b - root) : -0.5 * (b + root);
    if (q == 0.0) return false;  // the origin on the sphere, the ray tangent to it
    const double dist = std::sqrt(dot(oc, oc));
    double t0 = q / a, t1 = (dist - r) * (dist + r) / q;
    if (t0 > t1) std::swap(t0, t1);
    for (const double candidate : {t0, t1}) {
        if (candidate >= tnear && candidate <= tfar) {
            t = candidate;
            return true;
        }
    }
    return false;
}

void sphereHitPoint(const Sphere &sphere, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n) {
    const Vec3d c = toDouble(sphere.center);
    const Vec3d v{o.x + t * d.x - c.x, o.y + t * d.y - c.y, o.z + t * d.z - c.z};
    const double len = std::sqrt(dot(v, v));
    const Vec3d u = len > 0.0 ? Vec3d{v.x / len, v.y / len, v.z / len} : Vec3d{0.0, 0.0, 1.0};
    const double r = sphere.radius;
    p = Vec3f(float(c.x + r * u.x), float(c.y + r * u.y), float(c.z + r * u.z));
    const double sign = sphere.flipNormals ? -1.0 : 1.0;
    n = Vec3f(float(sign * u.x), float(sign * u.y), float(sign * u.z));
}

namespace {

void bounds(const RTCBoundsFunctionArguments *args) {
    const Sphere &s = *static_cast<const Sphere *>(args->geometryUserPtr);
    // Rounded outward: the float box must contain the double sphere.
    const auto down = [](double x) { return std::nextafter(float(x), -std::numeric_limits<float>::infinity()); };
    const auto up = [](double x) { return std::nextafter(float(x), std::numeric_limits<float>::infinity()); };
    const double r = s.radius;
    RTCBounds *b = args->bounds_o;
    b->lower_x = down(double(s.center.x) - r); b->upper_x = up(double(s.center.x) + r);
    b->lower_y = down(double(s.center.y) - r); b->upper_y = up(double(s.center.y) + r);
    b->lower_z = down(double(s.center.z) - r); b->upper_z = up(double(s.center.z) + r);
}

/// Ray i of an Embree packet of N (N is 1 for rtcIntersect1, up to 8 for rtcIntersect8).
struct RayView {
    RTCRayN *ray;
    unsigned N, i;
    Vec3f o() const { return {RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)}; }
    Vec3f d() const { return {RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)}; }
    float &tnear() const { return RTCRayN_tnear(ray, N, i); }
    float &tfar() const { return RTCRayN_tfar(ray, N, i); }
};

void intersect(const RTCIntersectFunctionNArguments *args) {
    const Sphere &s = *static_cast<const Sphere *>(args->geometryUserPtr);
    RTCRayN *rays = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN *hits = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const RayView ray{rays, args->N, i};
        double t;
        if (!intersectSphere(s, ray.o(), ray.d(), ray.tnear(), ray.tfar(), t)) continue;
        const float tf = float(t);
        if (tf > ray.tfar()) continue;  // rounded up past the closest hit so far
        ray.tfar() = tf;
        // u keeps what float32 rounded off t, so the hit point is rebuilt from t in double.
        RTCHitN_u(hits, args->N, i) = float(t - double(tf));
        RTCHitN_v(hits, args->N, i) = 0.f;
        RTCHitN_Ng_x(hits, args->N, i) = 0.f;
        RTCHitN_Ng_y(hits, args->N, i) = 0.f;
        RTCHitN_Ng_z(hits, args->N, i) = 1.f;
        RTCHitN_primID(hits, args->N, i) = args->primID;
        RTCHitN_geomID(hits, args->N, i) = args->geomID;
        RTCHitN_instID(hits, args->N, i, 0) = args->context->instID[0];
    }
}

void occluded(const RTCOccludedFunctionNArguments *args) {
    const Sphere &s = *static_cast<const Sphere *>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const RayView ray{args->ray, args->N, i};
        double t;
        if (intersectSphere(s, ray.o(), ray.d(), ray.tnear(), ray.tfar(), t))
            ray.tfar() = -std::numeric_limits<float>::infinity();  // Embree's mark of an occluded ray
    }
}

}  // namespace

void attachSphere(RTCDevice device, RTCScene scene, const Sphere &sphere) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, const_cast<Sphere *>(&sphere));
    rtcSetGeometryBoundsFunction(geom, bounds, nullptr);
    rtcSetGeometryIntersectFunction(geom, intersect);
    rtcSetGeometryOccludedFunction(geom, occluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
}

}  // namespace mcval
