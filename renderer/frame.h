// An orthonormal frame around a normal, for turning local samples into world directions.
#pragma once

#include <cmath>

#include "vector.h"

namespace mcval {

/// Tangent frame with n as its z axis (Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017).
struct Frame {
    Vec3f s, t, n;

    Frame() = default;
    explicit Frame(const Vec3f &normal) : n(normal) {
        const float sign = std::copysign(1.f, n.z);
        const float a = -1.f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = Vec3f(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Vec3f(b, sign + n.y * n.y * a, -n.y);
    }

    Vec3f toWorld(const Vec3f &v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace mcval
