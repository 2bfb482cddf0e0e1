// Mitsuba 3's envmap (src/emitters/envmap.cpp) as Mitsuba's RGB variants evaluate it: the image gains a column,
// a copy of its first, so that it wraps around; a direction's (u, v) = (atan2(x, -z) / 2 pi, acos(y) / pi) in
// the emitter's frame; u is shifted by half a pixel, so that pixel centres fall on grid points, and the four
// nearest points are interpolated bilinearly. Its sampling is ours (luminance per cell, uniform within), with
// the matching density: an estimate is the same whichever warp draws the directions.
#include "envmap.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "../warp.h"

namespace mcval {

namespace {

/// The bin of a cumulative table (its last entry the total) that `target` falls in, and where in it.
size_t findBin(const double *cdf, size_t n, double target, double &within) {
    const size_t i = std::min(size_t(std::upper_bound(cdf, cdf + n, target) - cdf), n - 1);
    const double lo = i == 0 ? 0.0 : cdf[i - 1], width = cdf[i] - lo;
    within = width > 0.0 ? std::clamp((target - lo) / width, 0.0, double(kOneMinusEpsilon)) : 0.5;
    return i;
}

constexpr float kMinSinTheta = std::numeric_limits<float>::epsilon();

}  // namespace

EnvmapEmitter::EnvmapEmitter(const EnvironmentMap &map)
    : m_width(map.image->width), m_height(map.image->height), m_toWorld(map.toWorld) {
    const int columns = m_width + 1;
    m_grid.resize(size_t(columns) * size_t(m_height) * 3);
    for (int y = 0; y < m_height; ++y)
        for (int x = 0; x < columns; ++x) {
            const float *in = map.image->at(x % m_width, y);
            float *out = &m_grid[3 * (size_t(y) * columns + x)];
            for (int c = 0; c < 3; ++c) out[c] = in[c] * map.scale;
        }
    const int rows = m_height - 1;
    m_rowCdf.resize(rows);
    m_cellCdf.resize(size_t(rows) * m_width);
    m_cellWeight.resize(size_t(rows) * m_width);
    const double thetaStep = M_PI / double(rows);
    for (int y = 0; y < rows; ++y) {
        const double sinMean = 0.5 * (std::sin(y * thetaStep) + std::sin((y + 1) * thetaStep));
        double row = 0.0;
        for (int x = 0; x < m_width; ++x) {
            const auto lum = [&](int gx, int gy) {
                const float *p = &m_grid[3 * (size_t(gy) * columns + gx)];
                return luminance({p[0], p[1], p[2]});
            };
            const double w = 0.25 * (lum(x, y) + lum(x + 1, y) + lum(x, y + 1) + lum(x + 1, y + 1)) * sinMean;
            m_cellWeight[size_t(y) * m_width + x] = float(w);
            row += w;
            m_cellCdf[size_t(y) * m_width + x] = row;
        }
        m_total += row;
        m_rowCdf[y] = m_total;
    }
}

Vec3f EnvmapEmitter::toLocal(const Vec3f &d) const { return normalize(m_toWorld.inverseVector(d)); }
Vec3f EnvmapEmitter::toWorld(const Vec3f &d) const { return normalize(m_toWorld.vector(d)); }

Vec2f EnvmapEmitter::gridOf(const Vec3f &local) const {
    // In float and in Mitsuba's order of operations, so that a direction lands between the same grid points.
    float u = std::atan2(local.x, -local.z) * kInv2Pi - 0.5f / float(m_width);
    float v = std::acos(std::clamp(local.y, -1.f, 1.f)) * kInvPi;
    u -= std::floor(u);
    v -= std::floor(v);
    return {u * float(m_width), v * float(m_height - 1)};
}

Color EnvmapEmitter::lookup(const Vec2f &grid) const {
    const int columns = m_width + 1;
    const int x = std::min(int(grid.x), m_width - 1), y = std::min(int(grid.y), m_height - 2);
    const float wx = grid.x - float(x), wy = grid.y - float(y);
    const float *p00 = &m_grid[3 * (size_t(y) * columns + x)];
    const float *p10 = p00 + 3, *p01 = p00 + 3 * columns, *p11 = p01 + 3;
    Color out;
    float *o = &out.x;
    for (int c = 0; c < 3; ++c) {
        const float top = (1.f - wx) * p00[c] + wx * p10[c], bottom = (1.f - wx) * p01[c] + wx * p11[c];
        o[c] = (1.f - wy) * top + wy * bottom;
    }
    return out;
}

float EnvmapEmitter::cellPdf(int cx, int cy, float sinTheta) const {
    if (!(m_total > 0.0)) return 0.f;
    const double cells = double(m_width) * double(m_height - 1);
    const double perUv = double(m_cellWeight[size_t(cy) * m_width + cx]) / m_total * cells;
    return float(perUv / (2.0 * M_PI * M_PI * std::max(sinTheta, kMinSinTheta)));
}

EmitterSample EnvmapEmitter::sample(const Vec3f &, const Vec2f &u) const {
    EmitterSample s;
    s.dist = std::numeric_limits<float>::infinity();
    if (!(m_total > 0.0)) return s;
    double fy, fx;
    const int cy = int(findBin(m_rowCdf.data(), m_rowCdf.size(), double(u.y) * m_total, fy));
    const double *row = &m_cellCdf[size_t(cy) * m_width];
    const int cx = int(findBin(row, size_t(m_width), double(u.x) * row[m_width - 1], fx));
    const Vec2f grid(float(cx + fx), float(cy + fy));
    const float theta = grid.y / float(m_height - 1) * kPi;
    const float phi = (grid.x + 0.5f) / float(m_width) * (2.f * kPi);
    const float sinTheta = std::sin(theta);
    const Vec3f local(std::sin(phi) * sinTheta, std::cos(theta), -std::cos(phi) * sinTheta);
    s.d = toWorld(local);
    s.n = -s.d;
    s.pdf = cellPdf(cx, cy, std::sqrt(local.x * local.x + local.z * local.z));
    if (!(s.pdf > 0.f)) return EmitterSample{};
    s.weight = lookup(grid) / s.pdf;
    return s;
}

Color EnvmapEmitter::eval(const EmitterHit &at) const { return lookup(gridOf(toLocal(at.d))); }

float EnvmapEmitter::pdf(const Vec3f &, const EmitterHit &at) const {
    const Vec3f local = toLocal(at.d);
    const Vec2f grid = gridOf(local);
    const int cx = std::min(int(grid.x), m_width - 1), cy = std::min(int(grid.y), m_height - 2);
    return cellPdf(cx, cy, std::sqrt(local.x * local.x + local.z * local.z));
}

}  // namespace mcval
