#include "sphere.h"

#include "hot.h"
#include "user_geometry.h"

#include <cmath>
#include <limits>
#include <utility>

namespace mcval {

namespace {

Vec3d toDouble(const Vec3f &v) { return Vec3d(v); }

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

void shapeBounds(const Sphere &sphere, Vec3d &lo, Vec3d &hi) {
    const double r = sphere.radius;
    lo = {double(sphere.center.x) - r, double(sphere.center.y) - r, double(sphere.center.z) - r};
    hi = {double(sphere.center.x) + r, double(sphere.center.y) + r, double(sphere.center.z) + r};
}

namespace {

/// intersectSphere for lanes [0, N) of an Embree RTCRayN at once, branch-free so that GCC turns the
/// loop into SIMD: the same operations in the same order (so the same bits), every root computed
/// and the early returns folded into the lane's mask. hit[i] is -1 where intersectSphere would
/// return true with t = t[i], else 0 (t[i] is then meaningless). Lanes Embree left invalid hold
/// whatever Embree left there; they are computed like the others and their results ignored.
template <unsigned N>
__attribute__((always_inline)) inline void sphereRoots(const Sphere &s, const float *__restrict ray,
                                                       double *__restrict tOut, long long *__restrict hitOut) {
    const double cx = s.center.x, cy = s.center.y, cz = s.center.z, r = s.radius;
    for (unsigned i = 0; i < N; ++i) {
        const double dx = ray[4 * N + i], dy = ray[5 * N + i], dz = ray[6 * N + i];
        const double ox = double(ray[0 * N + i]) - cx, oy = double(ray[1 * N + i]) - cy,
                     oz = double(ray[2 * N + i]) - cz;
        const double a = dx * dx + dy * dy + dz * dz;
        const double b = 2.0 * (dx * ox + dy * oy + dz * oz);
        const double k = b / (2.0 * a);
        const double vx = ox - k * dx, vy = oy - k * dy, vz = oz - k * dz;
        const double closest = __builtin_sqrt(vx * vx + vy * vy + vz * vz);
        const double disc = 4.0 * a * (r + closest) * (r - closest);
        const double root = __builtin_sqrt(disc);
        // b - root is b + -root exactly (IEEE defines it so); the select is of operands, not of
        // results, so GCC has no operation to sink into a branch (which -ftrapping-math keeps from
        // being if-converted on AVX2).
        const double q = -0.5 * (b + (b < 0.0 ? -root : root));
        const double dist = __builtin_sqrt(ox * ox + oy * oy + oz * oz);
        const double t0 = q / a, t1 = (dist - r) * (dist + r) / q;
        const bool swap = t0 > t1;
        const double lo = swap ? t1 : t0, hi = swap ? t0 : t1;
        const double tnear = ray[3 * N + i], tfar = ray[8 * N + i];
        const bool loIn = (lo >= tnear) & (lo <= tfar), hiIn = (hi >= tnear) & (hi <= tfar);
        const bool hit = (a > 0.0) & (disc >= 0.0) & (q != 0.0) & (loIn | hiIn);
        tOut[i] = loIn ? lo : hi;
        hitOut[i] = hit ? -1 : 0;
    }
}

/// Embree's intersect callback for a packet of N (16 or 8), the lanes at once.
template <unsigned N>
__attribute__((always_inline)) inline void intersectPacket(const RTCIntersectFunctionNArguments *args) {
    const Sphere &s = *static_cast<const Sphere *>(args->geometryUserPtr);
    float *__restrict ray = reinterpret_cast<float *>(args->rayhit);
    float *__restrict hitf = ray + 12 * N;
    unsigned *__restrict hitu = reinterpret_cast<unsigned *>(args->rayhit) + 12 * N;
    const int *__restrict valid = args->valid;
    double t[N];
    long long found[N];
    sphereRoots<N>(s, ray, t, found);
    float tf[N], u[N];
    int store[N];
    for (unsigned i = 0; i < N; ++i) {
        tf[i] = float(t[i]);
        // u keeps what float32 rounded off t, so the hit point is rebuilt from t in double.
        u[i] = float(t[i] - double(tf[i]));
        // Not where tf rounded up past the closest hit so far.
        store[i] = (valid[i] == -1) & (found[i] != 0) & !(tf[i] > ray[8 * N + i]);
    }
    // The stores apart, of values computed above: masked stores, nothing to compute under a mask.
    const unsigned primID = args->primID, geomID = args->geomID, instID = args->context->instID[0];
    for (unsigned i = 0; i < N; ++i) {
        if (store[i]) {
            ray[8 * N + i] = tf[i];
            hitf[3 * N + i] = u[i];
            hitf[4 * N + i] = 0.f;
            hitf[0 * N + i] = 0.f;
            hitf[1 * N + i] = 0.f;
            hitf[2 * N + i] = 1.f;
            hitu[5 * N + i] = primID;
            hitu[6 * N + i] = geomID;
            hitu[7 * N + i] = instID;
        }
    }
}

/// Embree's occluded callback for a packet of N (16 or 8), the lanes at once.
template <unsigned N>
__attribute__((always_inline)) inline void occludedPacket(const RTCOccludedFunctionNArguments *args) {
    const Sphere &s = *static_cast<const Sphere *>(args->geometryUserPtr);
    float *__restrict ray = reinterpret_cast<float *>(args->ray);
    const int *__restrict valid = args->valid;
    double t[N];
    long long found[N];
    sphereRoots<N>(s, ray, t, found);
    for (unsigned i = 0; i < N; ++i)
        if ((valid[i] == -1) & (found[i] != 0))
            ray[8 * N + i] = -std::numeric_limits<float>::infinity();  // Embree's mark of an occluded ray
}

// Packets of 16 and 8 (the renderer's and Embree's own) at once; any other width lane by lane.
MCVAL_HOT void intersect(const RTCIntersectFunctionNArguments *args) {
    if (args->N == 16) return intersectPacket<16>(args);
    if (args->N == 8) return intersectPacket<8>(args);
    user_geometry_detail::intersect<Sphere>(args);
}

MCVAL_HOT void occluded(const RTCOccludedFunctionNArguments *args) {
    if (args->N == 16) return occludedPacket<16>(args);
    if (args->N == 8) return occludedPacket<8>(args);
    user_geometry_detail::occluded<Sphere>(args);
}

}  // namespace

void attachSphere(RTCDevice device, RTCScene scene, const Sphere &sphere) {
    attachUserGeometry(device, scene, sphere, intersect, occluded);
}

}  // namespace mcval
