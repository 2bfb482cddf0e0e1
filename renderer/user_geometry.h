// An exact shape (sphere, disk, cylinder) as an Embree 3 user geometry: its bounds, and callbacks that
// intersect each lane of a packet on its own, in double (the sphere has packet kernels for 8 and 16 lanes
// and falls back on these for other widths).
#pragma once

#include <cmath>
#include <limits>

#include <embree3/rtcore.h>

#include "affine.h"
#include "vector.h"

namespace mcval {

namespace user_geometry_detail {

/// The box [lo, hi] rounded outward to float32, so that it contains the double shape.
inline void roundOut(const Vec3d &lo, const Vec3d &hi, RTCBounds *b) {
    constexpr float inf = std::numeric_limits<float>::infinity();
    const auto down = [](double x) { return std::nextafter(float(x), -inf); };
    const auto up = [](double x) { return std::nextafter(float(x), inf); };
    b->lower_x = down(lo.x); b->lower_y = down(lo.y); b->lower_z = down(lo.z);
    b->upper_x = up(hi.x); b->upper_y = up(hi.y); b->upper_z = up(hi.z);
}

template <typename Shape>
void bounds(const RTCBoundsFunctionArguments *args) {
    Vec3d lo, hi;
    shapeBounds(*static_cast<const Shape *>(args->geometryUserPtr), lo, hi);
    roundOut(lo, hi, args->bounds_o);
}

template <typename Shape>
void intersect(const RTCIntersectFunctionNArguments *args) {
    const Shape &shape = *static_cast<const Shape *>(args->geometryUserPtr);
    const unsigned N = args->N;
    RTCRayN *rays = RTCRayHitN_RayN(args->rayhit, N);
    RTCHitN *hits = RTCRayHitN_HitN(args->rayhit, N);
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        const Vec3f o{RTCRayN_org_x(rays, N, i), RTCRayN_org_y(rays, N, i), RTCRayN_org_z(rays, N, i)};
        const Vec3f d{RTCRayN_dir_x(rays, N, i), RTCRayN_dir_y(rays, N, i), RTCRayN_dir_z(rays, N, i)};
        float &tfar = RTCRayN_tfar(rays, N, i);
        double t;
        if (!intersectShape(shape, o, d, RTCRayN_tnear(rays, N, i), tfar, t)) continue;
        const float tf = float(t);
        if (tf > tfar) continue;  // rounded up past the closest hit so far
        tfar = tf;
        // u keeps what float32 rounded off t, so the hit point is rebuilt from t in double.
        RTCHitN_u(hits, N, i) = float(t - double(tf));
        RTCHitN_v(hits, N, i) = 0.f;
        RTCHitN_Ng_x(hits, N, i) = 0.f;
        RTCHitN_Ng_y(hits, N, i) = 0.f;
        RTCHitN_Ng_z(hits, N, i) = 1.f;
        RTCHitN_primID(hits, N, i) = args->primID;
        RTCHitN_geomID(hits, N, i) = args->geomID;
        RTCHitN_instID(hits, N, i, 0) = args->context->instID[0];
    }
}

template <typename Shape>
void occluded(const RTCOccludedFunctionNArguments *args) {
    const Shape &shape = *static_cast<const Shape *>(args->geometryUserPtr);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        RTCRayN *r = args->ray;
        const Vec3f o{RTCRayN_org_x(r, N, i), RTCRayN_org_y(r, N, i), RTCRayN_org_z(r, N, i)};
        const Vec3f d{RTCRayN_dir_x(r, N, i), RTCRayN_dir_y(r, N, i), RTCRayN_dir_z(r, N, i)};
        double t;
        if (intersectShape(shape, o, d, RTCRayN_tnear(r, N, i), RTCRayN_tfar(r, N, i), t))
            RTCRayN_tfar(r, N, i) = -std::numeric_limits<float>::infinity();  // Embree's mark of an occluded ray
    }
}

}  // namespace user_geometry_detail

/// Attaches `shape` to the scene as one Embree user geometry; it must outlive the scene. Shape needs
/// intersectShape(shape, o, d, tnear, tfar, double &t) and shapeBounds(shape, Vec3d &lo, Vec3d &hi). A shape
/// with packet kernels of its own (the sphere) gives its own intersect and occluded callbacks.
template <typename Shape>
void attachUserGeometry(RTCDevice device, RTCScene scene, const Shape &shape,
                        RTCIntersectFunctionN intersect = user_geometry_detail::intersect<Shape>,
                        RTCOccludedFunctionN occluded = user_geometry_detail::occluded<Shape>) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, 1);
    rtcSetGeometryUserData(geom, const_cast<Shape *>(&shape));
    rtcSetGeometryBoundsFunction(geom, user_geometry_detail::bounds<Shape>, nullptr);
    rtcSetGeometryIntersectFunction(geom, intersect);
    rtcSetGeometryOccludedFunction(geom, occluded);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
}

}  // namespace mcval
