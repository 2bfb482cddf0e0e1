// Small fixed-size vectors: only what the renderer needs.
#pragma once

#include <cmath>

namespace mcval {

/// A 2D point or vector of floats.
struct Vec2f {
    float x = 0.f, y = 0.f;
    constexpr Vec2f() = default;
    constexpr Vec2f(float x_, float y_) : x(x_), y(y_) {}
};

/// A 3D point, vector or normal of floats.
struct Vec3f {
    float x = 0.f, y = 0.f, z = 0.f;
    constexpr Vec3f() = default;
    constexpr Vec3f(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3f operator+(const Vec3f &o) const { return {x + o.x, y + o.y, z + o.z}; }
    constexpr Vec3f operator-(const Vec3f &o) const { return {x - o.x, y - o.y, z - o.z}; }
    constexpr Vec3f operator-() const { return {-x, -y, -z}; }
    constexpr Vec3f operator*(float s) const { return {x * s, y * s, z * s}; }
    constexpr Vec3f operator/(float s) const { return {x / s, y / s, z / s}; }
    constexpr Vec3f operator*(const Vec3f &o) const { return {x * o.x, y * o.y, z * o.z}; }
};

constexpr Vec3f operator*(float s, const Vec3f &v) { return v * s; }

/// Dot product.
constexpr float dot(const Vec3f &a, const Vec3f &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// Cross product (right-handed).
constexpr Vec3f cross(const Vec3f &a, const Vec3f &b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Squared Euclidean length.
constexpr float squaredNorm(const Vec3f &v) { return dot(v, v); }

/// Euclidean length.
inline float norm(const Vec3f &v) { return std::sqrt(dot(v, v)); }

/// Unit vector along v (v must not be zero).
inline Vec3f normalize(const Vec3f &v) { return v / norm(v); }

}  // namespace mcval
