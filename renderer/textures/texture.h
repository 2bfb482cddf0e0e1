// Mitsuba's textures of a reflectance, evaluated at a surface point's (u, v) as Mitsuba 3's RGB variants do:
// `bitmap` (an image, filtered and wrapped as Dr.Jit's textures are) and `checkerboard`.
#pragma once

#include <memory>
#include <vector>

#include "../bsdfs/bsdf.h"
#include "../transform.h"

namespace mcval {

/// Mitsuba's `to_uv`: the x and y rows of a <transform>, its translation in their last column (z dropped).
struct UvTransform {
    float m[2][3] = {{1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}};
    UvTransform() = default;
    explicit UvTransform(const Transform &t)
        : m{{t.m[0][0], t.m[0][1], t.m[0][3]}, {t.m[1][0], t.m[1][1], t.m[1][3]}} {}
    Vec2f apply(const Vec2f &uv) const {
        return {m[0][0] * uv.x + m[0][1] * uv.y + m[0][2], m[1][0] * uv.x + m[1][1] * uv.y + m[1][2]};
    }
};

class Texture {
public:
    virtual ~Texture() = default;
    /// The value at the surface's (u, v), before to_uv.
    virtual Color eval(const Vec2f &uv) const = 0;
    /// Its largest channel value anywhere: a reflectance must not exceed 1.
    virtual float maxValue() const = 0;
};

enum class WrapMode { Repeat, Mirror, Clamp };
enum class FilterMode { Bilinear, Nearest };

/// Linear RGB pixels, three floats each (a one-channel image repeats its value), row by row from the top: a
/// texture's (row 0 at v = 0) or an environment map's (row 0 at theta = 0).
struct RgbImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
    const float *at(int x, int y) const { return rgb.data() + 3 * (size_t(y) * size_t(width) + size_t(x)); }
};

class BitmapTexture final : public Texture {
public:
    BitmapTexture(std::shared_ptr<const RgbImage> image, WrapMode wrap, FilterMode filter, const UvTransform &toUv)
        : m_image(std::move(image)), m_wrap(wrap), m_filter(filter), m_toUv(toUv) {}
    /// Pixel centres at ((i + 1/2) / width, (j + 1/2) / height); bilinear between the four nearest, or the
    /// nearest alone; indices beyond the image wrapped by the wrap mode.
    Color eval(const Vec2f &uv) const override;
    float maxValue() const override;

private:
    int wrap(int i, int n) const;
    Color pixel(int x, int y) const;
    std::shared_ptr<const RgbImage> m_image;
    WrapMode m_wrap;
    FilterMode m_filter;
    UvTransform m_toUv;
};

class CheckerboardTexture final : public Texture {
public:
    CheckerboardTexture(const Color &color0, const Color &color1, const UvTransform &toUv)
        : m_color0(color0), m_color1(color1), m_toUv(toUv) {}
    /// color0 where the fractional parts of u and v are both above 1/2 or both not, color1 elsewhere.
    Color eval(const Vec2f &uv) const override;
    float maxValue() const override;

private:
    Color m_color0, m_color1;
    UvTransform m_toUv;
};

}  // namespace mcval
