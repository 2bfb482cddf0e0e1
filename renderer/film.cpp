#include "film.h"

#include <algorithm>
#include <cmath>

#include "hot.h"
#include "scene_limits.h"

namespace mcval {

ImageBlock::ImageBlock(int x0, int y0, int width, int height, const FilterSpec &filter)
    : m_filter(filter), m_radius(filter.radius()) {
    static_assert(kMaxTaps >= 2 * 4 * kMaxFilterStddev + 2, "a gaussian's taps must fit wxs in put()");
    static_assert(kMaxTaps >= 2 * kMaxTentRadius + 2, "a tent's taps must fit wxs in put()");
    if (filter.type != FilterSpec::Type::Box) {  // weight()'s constants, once per block
        if (filter.type == FilterSpec::Type::Gaussian) {
            m_alpha = -1.f / (2.f * filter.stddev * filter.stddev);
            m_edge = expNonPositive(m_alpha * m_radius * m_radius);
        } else {
            m_invRadius = 1.f / m_radius;
        }
        m_taps = static_cast<int>(std::floor(m_radius + 0.5f));
        const size_t taps = 2 * static_cast<size_t>(m_taps) + 1;
        m_scratch.assign(4 * taps * kMaxPacket + 8, 0.0);  // putWide: a, a^2, b, b^2 per tap and lane
    }
    const int border = static_cast<int>(std::ceil(m_radius - 0.5f));
    m_x0 = x0 - border;
    m_y0 = y0 - border;
    m_width = width + 2 * border;
    m_height = height + 2 * border;
    m_data.assign(static_cast<size_t>(kStride) * m_width * m_height, 0.0);
}

MCVAL_HOT void ImageBlock::put(float x, float y, const Color &L) {
    // Pixel (i, j) has its centre at (i + 0.5, j + 0.5), as in Mitsuba.
    const int ilo = std::max(static_cast<int>(std::ceil(x - 0.5f - m_radius)), m_x0);
    const int ihi = std::min(static_cast<int>(std::floor(x - 0.5f + m_radius)), m_x0 + m_width - 1);
    const int jlo = std::max(static_cast<int>(std::ceil(y - 0.5f - m_radius)), m_y0);
    const int jhi = std::min(static_cast<int>(std::floor(y - 0.5f + m_radius)), m_y0 + m_height - 1);
    // The separable filter's weights along each axis, once per sample rather than once per pixel.
    float wxs[kMaxTaps];
    for (int i = ilo; i <= ihi; ++i) wxs[i - ilo] = weight(static_cast<float>(i) + 0.5f - x);
    for (int j = jlo; j <= jhi; ++j) {
        const float wy = weight(static_cast<float>(j) + 0.5f - y);
        if (wy == 0.f) continue;
        for (int i = ilo; i <= ihi; ++i) {
            const double w = static_cast<double>(wy) * wxs[i - ilo];
            if (w == 0.0) continue;
            double *s = &m_data[kStride * ((j - m_y0) * m_width + (i - m_x0))];
            const double w2 = w * w;
            s[0] += w;
            s[4] += w2;
            for (int c = 0; c < 3; ++c) {
                const double l = L[c];
                s[1 + c] += w * l;
                s[5 + c] += w2 * l;
                s[8 + c] += w2 * l * l;
            }
        }
    }
}

void ImageBlock::putBox(int x, int y, const Color *L, int count) {
    double sum[3] = {0.0, 0.0, 0.0}, sum2[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < count; ++k)
        for (int c = 0; c < 3; ++c) {
            const double l = L[k][c];
            sum[c] += l;
            sum2[c] += l * l;
        }
    double *s = &m_data[kStride * ((y - m_y0) * m_width + (x - m_x0))];
    s[0] += count;
    s[4] += count;
    for (int c = 0; c < 3; ++c) {
        s[1 + c] += sum[c];
        s[5 + c] += sum[c];
        s[8 + c] += sum2[c];
    }
}

void ImageBlock::putPacket(int x, int y, const float *fx, const float *fy, const Color *L, int count) {
    if (isBox()) {
        putBox(x, y, L, count);  // a box filter keeps every sample in its own pixel
        return;
    }
    putWide(x, y, fx, fy, L, count);
}

Film::Film(int width, int height, int x0, int y0)
    : m_width(width), m_height(height), m_x0(x0), m_y0(y0), m_data(static_cast<size_t>(ImageBlock::kChannels) * width * height, 0.0) {}

void Film::merge(const ImageBlock &block) {
    for (int j = 0; j < block.height(); ++j) {
        const int y = block.y0() + j - m_y0;
        if (y < 0 || y >= m_height) continue;
        for (int i = 0; i < block.width(); ++i) {
            const int x = block.x0() + i - m_x0;
            if (x < 0 || x >= m_width) continue;
            const double *src = block.sums(i, j);
            double *dst = &m_data[ImageBlock::kChannels * (y * m_width + x)];
            for (int c = 0; c < ImageBlock::kChannels; ++c) dst[c] += src[c];
        }
    }
}

void Film::develop(std::vector<float> &mean, std::vector<float> &variance) const {
    const size_t n = static_cast<size_t>(m_width) * m_height;
    mean.assign(3 * n, 0.f);
    variance.assign(3 * n, 0.f);
    for (size_t p = 0; p < n; ++p) {
        const double *s = &m_data[ImageBlock::kChannels * p];
        const double w = s[0], w2 = s[4];
        if (!(w > 0.0)) continue;
        // Effective sample count of a weighted mean; the variance needs at least two.
        const double nEff = w * w / w2;
        for (int c = 0; c < 3; ++c) {
            const double m = s[1 + c] / w;
            mean[3 * p + c] = static_cast<float>(m);
            if (nEff > 1.0 + 1e-9) {
                const double spread = std::max(0.0, s[8 + c] - 2.0 * m * s[5 + c] + m * m * w2);
                variance[3 * p + c] = static_cast<float>(spread / (w * w) * nEff / (nEff - 1.0));
            }
        }
    }
}

}  // namespace mcval
