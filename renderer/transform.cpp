#include "transform.h"

#include <cmath>

#include <stdexcept>

namespace mcval {

namespace {

void identity(float a[4][4]) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) a[i][j] = i == j ? 1.f : 0.f;
}

/// Inverse by Gauss-Jordan elimination with partial pivoting (in double).
bool invert(const float a[4][4], float out[4][4]) {
    double w[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 8; ++j) w[i][j] = j < 4 ? a[i][j] : (j - 4 == i ? 1.0 : 0.0);
    for (int c = 0; c < 4; ++c) {
        int p = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(w[r][c]) > std::abs(w[p][c])) p = r;
        if (w[p][c] == 0.0) return false;
        for (int j = 0; j < 8; ++j) std::swap(w[c][j], w[p][j]);
        const double d = w[c][c];
        for (int j = 0; j < 8; ++j) w[c][j] /= d;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            const double f = w[r][c];
            for (int j = 0; j < 8; ++j) w[r][j] -= f * w[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out[i][j] = static_cast<float>(w[i][j + 4]);
    return true;
}

}  // namespace

Transform::Transform() {
    identity(m);
    identity(inv);
}

Transform::Transform(const float a[16]) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m[i][j] = a[4 * i + j];
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(a[i])) throw std::domain_error("transform is not finite (it overflows float32)");
    if (!invert(m, inv)) throw std::domain_error("transform matrix is singular");
    for (const auto &row : inv)
        for (float x : row)
            if (!std::isfinite(x)) throw std::domain_error("transform is too close to singular to invert in float32");
}

Transform Transform::translate(const Vec3f &t) {
    const float a[16] = {1, 0, 0, t.x, 0, 1, 0, t.y, 0, 0, 1, t.z, 0, 0, 0, 1};
    return Transform(a);
}

Transform Transform::scale(const Vec3f &s) {
    const float a[16] = {s.x, 0, 0, 0, 0, s.y, 0, 0, 0, 0, s.z, 0, 0, 0, 0, 1};
    return Transform(a);
}

Transform Transform::rotate(const Vec3f &axisIn, float degrees) {
    const Vec3f a = normalize(axisIn);
    const float rad = degrees * 3.14159265358979323846f / 180.f;
    const float s = std::sin(rad), c = std::cos(rad), t = 1.f - c;
    const float r[16] = {a.x * a.x * t + c,       a.x * a.y * t - a.z * s, a.x * a.z * t + a.y * s, 0,
                         a.x * a.y * t + a.z * s, a.y * a.y * t + c,       a.y * a.z * t - a.x * s, 0,
                         a.x * a.z * t - a.y * s, a.y * a.z * t + a.x * s, a.z * a.z * t + c,       0,
                         0, 0, 0, 1};
    return Transform(r);
}

Transform Transform::lookAt(const Vec3f &origin, const Vec3f &target, const Vec3f &up) {
    const Vec3f dir = normalize(target - origin);
    const Vec3f left = normalize(cross(up, dir));
    const Vec3f newUp = cross(dir, left);
    const float a[16] = {left.x, newUp.x, dir.x, origin.x, left.y, newUp.y, dir.y, origin.y,
                         left.z, newUp.z, dir.z, origin.z, 0, 0, 0, 1};
    return Transform(a);
}

Transform Transform::operator*(const Transform &o) const {
    float a[16];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            float s = 0.f;
            for (int k = 0; k < 4; ++k) s += m[i][k] * o.m[k][j];
            a[4 * i + j] = s;
        }
    return Transform(a);
}

Vec3f Transform::point(const Vec3f &p) const {
    const float x = m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3];
    const float y = m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3];
    const float z = m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3];
    const float w = m[3][0] * p.x + m[3][1] * p.y + m[3][2] * p.z + m[3][3];
    return w == 1.f ? Vec3f(x, y, z) : Vec3f(x, y, z) / w;
}

Vec3f Transform::vector(const Vec3f &v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

Vec3f Transform::inverseVector(const Vec3f &v) const {
    return {inv[0][0] * v.x + inv[0][1] * v.y + inv[0][2] * v.z, inv[1][0] * v.x + inv[1][1] * v.y + inv[1][2] * v.z,
            inv[2][0] * v.x + inv[2][1] * v.y + inv[2][2] * v.z};
}

bool Transform::orthonormal(double tolerance) const {
    for (int i = 0; i < 3; ++i)
        for (int j = i; j < 3; ++j) {
            const double dot = double(m[0][i]) * m[0][j] + double(m[1][i]) * m[1][j] + double(m[2][i]) * m[2][j];
            if (!(std::abs(dot - (i == j ? 1.0 : 0.0)) <= tolerance)) return false;
        }
    return true;
}

Vec3f Transform::normal(const Vec3f &n) const {
    return {inv[0][0] * n.x + inv[1][0] * n.y + inv[2][0] * n.z, inv[0][1] * n.x + inv[1][1] * n.y + inv[2][1] * n.z,
            inv[0][2] * n.x + inv[1][2] * n.y + inv[2][2] * n.z};
}

float Transform::determinant3() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

}  // namespace mcval
