// An affine map in double precision, with its inverse: the object-to-world map of an exact shape
// (disk, cylinder), applied where float32 would misplace hit points far from the origin.
#pragma once

#include <cmath>

#include "transform.h"
#include "vector.h"

namespace mcval {

/// A 3D point or vector of doubles.
struct Vec3d {
    double x = 0.0, y = 0.0, z = 0.0;
    constexpr Vec3d() = default;
    constexpr Vec3d(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    explicit constexpr Vec3d(const Vec3f &v) : x(v.x), y(v.y), z(v.z) {}
    constexpr Vec3d operator+(const Vec3d &o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3d operator-(const Vec3d &o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3d operator*(double s) const { return {x * s, y * s, z * s}; }
    Vec3f toFloat() const { return {float(x), float(y), float(z)}; }
};

constexpr double dot(const Vec3d &a, const Vec3d &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3d cross(const Vec3d &a, const Vec3d &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3d &v) { return std::sqrt(dot(v, v)); }

/// p -> a p + b, with a's inverse, all in double.
struct Affine {
    double a[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};  ///< linear part, row-major (columns: the images of the axes)
    Vec3d b;                                              ///< translation
    double inv[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

    /// The affine part of a 4x4 transform (its last row is (0, 0, 0, 1) for every <transform>).
    static Affine from(const Transform &t) {
        Affine f;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) f.a[i][j] = t.m[i][j];
        f.b = {t.m[0][3], t.m[1][3], t.m[2][3]};
        f.invert();
        return f;
    }
    /// The map whose linear part has columns c0, c1, c2, followed by a translation by t.
    static Affine fromColumns(const Vec3d &c0, const Vec3d &c1, const Vec3d &c2, const Vec3d &t) {
        Affine f;
        const Vec3d c[3] = {c0, c1, c2};
        for (int j = 0; j < 3; ++j) {
            f.a[0][j] = c[j].x;
            f.a[1][j] = c[j].y;
            f.a[2][j] = c[j].z;
        }
        f.b = t;
        f.invert();
        return f;
    }
    /// this * o: `o` applies first.
    Affine operator*(const Affine &o) const {
        Affine f;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) f.a[i][j] = a[i][0] * o.a[0][j] + a[i][1] * o.a[1][j] + a[i][2] * o.a[2][j];
        f.b = point(o.b);
        f.invert();
        return f;
    }
    double determinant() const {
        return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
               a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    }
    /// Column j: the image of axis j.
    Vec3d column(int j) const { return {a[0][j], a[1][j], a[2][j]}; }
    Vec3d vector(const Vec3d &v) const {
        return {a[0][0] * v.x + a[0][1] * v.y + a[0][2] * v.z, a[1][0] * v.x + a[1][1] * v.y + a[1][2] * v.z,
                a[2][0] * v.x + a[2][1] * v.y + a[2][2] * v.z};
    }
    Vec3d point(const Vec3d &p) const { return vector(p) + b; }
    /// The inverse map's linear part applied to v.
    Vec3d inverseVector(const Vec3d &v) const {
        return {inv[0][0] * v.x + inv[0][1] * v.y + inv[0][2] * v.z,
                inv[1][0] * v.x + inv[1][1] * v.y + inv[1][2] * v.z,
                inv[2][0] * v.x + inv[2][1] * v.y + inv[2][2] * v.z};
    }
    Vec3d inversePoint(const Vec3d &p) const { return inverseVector(p - b); }
    /// An object-space normal in world space (the inverse transpose), not normalised.
    Vec3d normal(const Vec3d &n) const {
        return {inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z,
                inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
                inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z};
    }

private:
    /// inv from a by cofactors; a singular a leaves non-finite entries (the loaders refuse it first).
    void invert() {
        const double d = determinant();
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                // inv[i][j] = cofactor(j, i) / det
                const int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
                inv[i][j] = (a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0]) / d;
            }
    }
};

/// Whether the linear part is degenerate: a zero column, or columns so nearly dependent that the
/// volume they span is below 1e-6 of the product of their lengths (a flattened or collapsed map).
inline bool isDegenerate(const Affine &f) {
    const double l0 = norm(f.column(0)), l1 = norm(f.column(1)), l2 = norm(f.column(2));
    return !(std::abs(f.determinant()) >= 1e-6 * l0 * l1 * l2 && l0 > 0.0 && l1 > 0.0 && l2 > 0.0);
}

}  // namespace mcval
