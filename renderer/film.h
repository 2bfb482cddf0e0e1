// Splatting samples through the reconstruction filter, and developing mean and variance.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "log_exp.h"
#include "ray.h"
#include "scene.h"

namespace mcval {

/// Per-pixel sums (in double) for the pixels a tile's samples can reach: the tile plus a
/// border as wide as the filter. Each tile has its own block, so threads never share one.
class ImageBlock {
public:
    ImageBlock(int x0, int y0, int width, int height, const FilterSpec &filter);

    /// Adds radiance L sampled at film position (x, y) to every pixel the filter reaches.
    void put(float x, float y, const Color &L);
    /// Adds `count` samples L[0..count) of pixel (x, y) with weight 1: put() for a box filter, whose
    /// weight is 1 inside the pixel the sample lies in and 0 elsewhere.
    void putBox(int x, int y, const Color *L, int count);
    /// Adds `count` (at most kMaxPacket) samples of pixel (x, y): L[k] at film position (fx[k], fy[k]),
    /// each inside the pixel. The same sums as put() per sample, to rounding.
    void putPacket(int x, int y, const float *fx, const float *fy, const Color *L, int count);
    bool isBox() const { return m_filter.type == FilterSpec::Type::Box; }

    int x0() const { return m_x0; }
    int y0() const { return m_y0; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    /// The sums at block pixel (i, j): w, w L (3), w^2, w^2 L (3), w^2 L^2 (3).
    const double *sums(int i, int j) const { return &m_data[kStride * (j * m_width + i)]; }

    static constexpr int kChannels = 11;
    /// Doubles per pixel in a block: the sums and a 0, so that putWide adds whole SIMD vectors
    /// (4 + 8) to a pixel, at the same offsets every time (their stores then forward to its loads).
    static constexpr int kStride = 12;
    /// Pixels a sample reaches along one axis: 2 x the widest filter radius (4 x kMaxFilterStddev) + 1.
    static constexpr int kMaxTaps = 2 * 16 + 2;
    /// Most samples putPacket() takes at once: a packet of rays.
    static constexpr int kMaxPacket = kPacketSize;

private:
    /// The filter's 1D weight at offset x (pixels); the 2D weight is separable. The gaussian is
    /// Mitsuba's windowed one, shifted so that it reaches 0 at the radius; the tent is Mitsuba's.
    float weight(float x) const {
        if (m_filter.type == FilterSpec::Type::Box) return std::abs(x) <= 0.5f ? 1.f : 0.f;
        if (m_filter.type == FilterSpec::Type::Tent) return tentWeight(x, m_invRadius);
        return std::max(0.f, expNonPositive(m_alpha * x * x) - m_edge);
    }
    static float tentWeight(float x, float invRadius) { return std::max(0.f, 1.f - std::abs(x * invRadius)); }
    /// putPacket() for a filter wider than a pixel, gaussian or tent (film_splat.cpp).
    void putWide(int x, int y, const float *fx, const float *fy, const Color *L, int count);

    FilterSpec m_filter;
    float m_radius;
    float m_alpha = 0.f, m_edge = 0.f;  ///< gaussian: -1 / (2 stddev^2), and its value at the radius
    float m_invRadius = 0.f;            ///< tent: 1 / radius
    int m_taps = 0;                     ///< the pixels x - m_taps .. x + m_taps a pixel x's samples reach
    std::vector<double> m_scratch;      ///< putWide()'s per-packet weights
    int m_x0, m_y0, m_width, m_height;
    std::vector<double> m_data;
};

/// The whole image's sums; blocks are merged in a fixed order, so the result is the same
/// whatever the thread count.
class Film {
public:
    /// An image of width x height pixels whose top-left is film pixel (x0, y0) (a crop window's offset).
    Film(int width, int height, int x0 = 0, int y0 = 0);
    void merge(const ImageBlock &block);

    /// Mean radiance per pixel (RGB, row-major from the top-left), and the variance of that mean
    /// estimated from the weighted spread of the samples (with an effective-count correction).
    void develop(std::vector<float> &mean, std::vector<float> &variance) const;

private:
    int m_width, m_height, m_x0, m_y0;
    std::vector<double> m_data;
};

}  // namespace mcval
