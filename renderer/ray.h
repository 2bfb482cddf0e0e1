// Rays, hits, and the robust offset that keeps secondary rays off their own surface.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "float_bits.h"
#include "vector.h"

namespace mcval {

/// Rays traced together as one Embree packet: the samples of a pixel, or the shadow rays they
/// spawn. 16 is AVX-512's width; Embree splits a packet on narrower machines.
constexpr int kPacketSize = 16;

/// A ray o + t d for t in [tnear, tfar]; d need not be unit length.
struct Ray {
    Vec3f o, d;
    float tnear = 0.f;
    float tfar = 1e30f;
};

/// The first surface a ray meets.
struct Hit {
    float t = 0.f;
    Vec3f p;          ///< position, from the barycentrics (more exact than o + t d)
    Vec3f ng;         ///< unit geometric normal; its side is the front
    Vec3f ns;         ///< unit shading normal (interpolated, or ng for flat meshes)
    uint32_t geom = 0;  ///< Embree geometry id: a mesh's index, or an exact shape's after the meshes
    uint32_t prim = 0;
    float offsetFloor = 0.f;  ///< smallest offset of a ray leaving the hit (offsetRayOrigin): see hitOffsetFloor
    int emitter = -1;   ///< the area emitter of the surface hit (an index into SceneEmitters), or -1
};

/// Moves p off its surface to the side of n (the unit geometric normal, flipped toward where the
/// ray goes), far enough that the ray cannot re-hit its own surface at any scene scale.
///
/// Each coordinate moves by the larger of two offsets. One is Waechter and Binder's (Ray Tracing
/// Gems, 2019): a fixed number of ulps of the coordinate, so it grows with the position's magnitude
/// and stays tight far from the origin. The other is `floor`, a length given by the size of the
/// scene's smallest shape (see EmbreeScene), so that the offset scales with the scene: an absolute
/// floor is a unit-scale choice that swallows millimetre geometry and vanishes on kilometre geometry.
/// A triangle hit raises its floor to the bound on its own rounding (hitOffsetFloor), which the ulps of
/// p miss where its vertices are much larger than p.
inline float offsetCoordinate(float x, float nx, float floor) {
    constexpr float kIntScale = 256.f;
    // Stepping the bits of 0 or a denormal could cross zero into a NaN; there the floor rules anyway.
    // Written without branches, so that a packet's lanes compute it in SIMD.
    // Unsigned arithmetic: the step of a discarded lane (-0 or a denormal) may wrap, harmlessly.
    const auto step = static_cast<uint32_t>(static_cast<int32_t>(kIntScale * nx));
    const float stepped = detail::bitsToFloat(detail::floatToBits(x) + ((x < 0.f) ? 0u - step : step));
    const float moved = std::abs(x) >= std::numeric_limits<float>::min() ? stepped : x;
    const float floored = x + floor * nx;
    return nx >= 0.f ? std::max(moved, floored) : std::min(moved, floored);
}

/// The bound on a triangle hit point's rounding per unit of |b0 p0| + |b1 p1| + |b2 p2| (pbrt-v4's
/// gamma(7), rounded up): p = b0 p0 + b1 p1 + b2 p2 in float is off its triangle's plane by at most this
/// much of the vertices' magnitudes, not of |p|. Where large vertices cancel to a small p (a big floor's
/// middle, once the floor is turned off the axes) that is many ulps of p, which the ulp offset misses.
constexpr float kTriangleErrorPerMagnitude = 8.f * 0x1p-24f;

/// Hit::offsetFloor of a point interpolated on a triangle (barycentrics w, u, v of p0, p1, p2; unit
/// geometric normal n): the scene's floor, or the bound on the point's distance from the triangle's plane
/// along n where that is larger. Exact vertex coordinates give an exact zero (an axis-aligned floor keeps
/// the scene's floor). Written without branches, for the packet's SIMD loop.
inline float hitOffsetFloor(float sceneFloor, const Vec3f &p0, const Vec3f &p1, const Vec3f &p2, float w, float u,
                            float v, const Vec3f &n) {
    const float ex = std::abs(p0.x * w) + std::abs(p1.x * u) + std::abs(p2.x * v);
    const float ey = std::abs(p0.y * w) + std::abs(p1.y * u) + std::abs(p2.y * v);
    const float ez = std::abs(p0.z * w) + std::abs(p1.z * u) + std::abs(p2.z * v);
    const float alongNormal = std::abs(n.x) * ex + std::abs(n.y) * ey + std::abs(n.z) * ez;
    return std::max(sceneFloor, kTriangleErrorPerMagnitude * alongNormal);
}

inline Vec3f offsetRayOrigin(const Vec3f &p, const Vec3f &n, float floor) {
    return {offsetCoordinate(p.x, n.x, floor), offsetCoordinate(p.y, n.y, floor), offsetCoordinate(p.z, n.z, floor)};
}

/// The origin of a ray leaving surface point p (unit geometric normal ng) in direction d without
/// re-hitting its surface: moved off the surface along ng, on the side d leaves by, by an offset that
/// scales with the position's magnitude and with `floor` (the size of the scene's smallest shape).
inline Vec3f spawnOrigin(const Vec3f &p, const Vec3f &ng, float floor, const Vec3f &d) {
    const Vec3f side = dot(ng, d) >= 0.f ? ng : -ng;
    return offsetRayOrigin(p, side, floor);
}

}  // namespace mcval
