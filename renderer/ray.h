// Rays, hits, and the robust offset that keeps secondary rays off their own surface.
#pragma once

#include <cstdint>
#include <cstring>

#include "vector.h"

namespace mcr {

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
    uint32_t mesh = 0;
    uint32_t prim = 0;
};

/// Moves p off its surface to the side of n (the geometric normal, flipped toward where the ray
/// goes) by a few ulps of p's coordinates, so the offset scales with the position's magnitude.
/// Waechter and Binder, "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems, 2019.
inline Vec3f offsetRayOrigin(const Vec3f &p, const Vec3f &n) {
    constexpr float kOrigin = 1.f / 32.f, kFloatScale = 1.f / 65536.f, kIntScale = 256.f;
    const auto shift = [&](float x, float nx) {
        if (std::abs(x) < kOrigin) return x + kFloatScale * nx;  // near 0 ulps are tiny: a fixed step
        int32_t bits;
        std::memcpy(&bits, &x, 4);
        const auto step = static_cast<int32_t>(kIntScale * nx);
        bits += (x < 0.f) ? -step : step;
        float out;
        std::memcpy(&out, &bits, 4);
        return out;
    };
    return {shift(p.x, n.x), shift(p.y, n.y), shift(p.z, n.z)};
}

}  // namespace mcr
