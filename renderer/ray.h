// Rays, hits, and the robust offset that keeps secondary rays off their own surface.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "vector.h"

namespace mcval {

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
    uint32_t geom = 0;  ///< Embree geometry id: a mesh's index, or a sphere's after the meshes
    uint32_t prim = 0;
};

/// Moves p off its surface to the side of n (the unit geometric normal, flipped toward where the
/// ray goes), far enough that the ray cannot re-hit its own triangle at any scene scale.
///
/// The offset is Waechter and Binder's "fast and robust" one (Ray Tracing Gems, 2019): a fixed
/// number of ulps of each coordinate, so it grows with the position's magnitude and stays tight far
/// from the origin. Near the origin, where ulps are tiny, it is floored at Mitsuba 3's offset for a
/// unit-sized position, 2 * 1500 float epsilons: a smaller offset changes which shadow rays graze a
/// neighbouring facet at the shadow terminator of smooth-shaded meshes, a difference from the
/// reference that the image tests detect (highpoly, simple).
inline Vec3f offsetRayOrigin(const Vec3f &p, const Vec3f &n) {
    constexpr float kOrigin = 1.f / 32.f, kFloatScale = 1.f / 65536.f, kIntScale = 256.f;
    constexpr float kFloor = 2.f * 1500.f * 0x1p-24f;
    const auto shift = [](float x, float nx) {
        float moved;
        if (std::abs(x) < kOrigin) {
            moved = x + kFloatScale * nx;  // near 0 ulps are tiny: a fixed step
        } else {
            int32_t bits;
            std::memcpy(&bits, &x, 4);
            const auto step = static_cast<int32_t>(kIntScale * nx);
            bits += (x < 0.f) ? -step : step;
            std::memcpy(&moved, &bits, 4);
        }
        const float floored = x + kFloor * nx;
        return nx >= 0.f ? std::max(moved, floored) : std::min(moved, floored);
    };
    return {shift(p.x, n.x), shift(p.y, n.y), shift(p.z, n.z)};
}

}  // namespace mcval
