// Affine transforms as 4x4 matrices, composed the way Mitsuba's <transform> elements are.
#pragma once

#include "vector.h"

namespace mcval {

/// A 4x4 row-major matrix acting on column vectors.
class Transform {
public:
    Transform();  ///< identity
    /// Throws std::domain_error if m is not finite or not invertible in float32.
    explicit Transform(const float m[16]);

    static Transform translate(const Vec3f &t);
    static Transform scale(const Vec3f &s);
    /// Rotation by `degrees` about `axis` (right-handed).
    static Transform rotate(const Vec3f &axis, float degrees);
    /// Camera-to-world frame: columns left, up, dir, origin (Mitsuba's look_at).
    static Transform lookAt(const Vec3f &origin, const Vec3f &target, const Vec3f &up);

    /// this * other: `other` is applied first.
    Transform operator*(const Transform &other) const;

    Vec3f point(const Vec3f &p) const;
    Vec3f vector(const Vec3f &v) const;
    /// The inverse's linear part applied to v: a world direction in the transform's own space.
    Vec3f inverseVector(const Vec3f &v) const;
    /// Whether the linear part's columns are orthonormal within `tolerance`: a rotation, possibly mirrored, that
    /// keeps directions unit (Mitsuba's Transform::has_scale tests 1e-3).
    bool orthonormal(double tolerance) const;
    /// Normals transform with the inverse transpose.
    Vec3f normal(const Vec3f &n) const;
    /// Determinant of the linear part: negative for a mirroring transform.
    float determinant3() const;

    float m[4][4];
    float inv[4][4];
};

}  // namespace mcval
