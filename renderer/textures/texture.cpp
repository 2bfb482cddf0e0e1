#include "texture.h"

#include <algorithm>
#include <cmath>

namespace mcval {

namespace {

float maxChannel(const Color &c) { return std::max(c.x, std::max(c.y, c.z)); }

}  // namespace

int BitmapTexture::wrap(int i, int n) const {
    switch (m_wrap) {
        case WrapMode::Clamp:
            return std::clamp(i, 0, n - 1);
        case WrapMode::Mirror: {
            int k = i % (2 * n);
            if (k < 0) k += 2 * n;
            return k < n ? k : 2 * n - 1 - k;
        }
        case WrapMode::Repeat:
        default: {
            const int k = i % n;
            return k < 0 ? k + n : k;
        }
    }
}

Color BitmapTexture::pixel(int x, int y) const {
    const float *p = &m_image->rgb[3 * (size_t(wrap(y, m_image->height)) * size_t(m_image->width) +
                                        size_t(wrap(x, m_image->width)))];
    return {p[0], p[1], p[2]};
}

Color BitmapTexture::eval(const Vec2f &surfaceUv) const {
    const Vec2f uv = m_toUv.apply(surfaceUv);
    const float w = float(m_image->width), h = float(m_image->height);
    // Far outside [0, 1] an index would overflow int: the wrap makes it periodic or constant there anyway.
    const auto index = [](float x) { return int(std::clamp(std::floor(x), -1e8f, 1e8f)); };
    if (m_filter == FilterMode::Nearest) return pixel(index(uv.x * w), index(uv.y * h));
    const float x = uv.x * w - 0.5f, y = uv.y * h - 0.5f;
    const int x0 = index(x), y0 = index(y);
    const float fx = std::isfinite(x) ? x - std::floor(x) : 0.f, fy = std::isfinite(y) ? y - std::floor(y) : 0.f;
    const Color top = pixel(x0, y0) * (1.f - fx) + pixel(x0 + 1, y0) * fx;
    const Color bottom = pixel(x0, y0 + 1) * (1.f - fx) + pixel(x0 + 1, y0 + 1) * fx;
    return top * (1.f - fy) + bottom * fy;
}

float BitmapTexture::maxValue() const {
    float m = 0.f;
    for (float v : m_image->rgb) m = std::max(m, v);
    return m;
}

Color CheckerboardTexture::eval(const Vec2f &surfaceUv) const {
    const Vec2f uv = m_toUv.apply(surfaceUv);
    const bool x = uv.x - std::floor(uv.x) > 0.5f, y = uv.y - std::floor(uv.y) > 0.5f;
    return x == y ? m_color0 : m_color1;
}

float CheckerboardTexture::maxValue() const { return std::max(maxChannel(m_color0), maxChannel(m_color1)); }

}  // namespace mcval
