// Reading an OpenEXR image's colour as 32-bit floats: an environment map's radiance.
#pragma once

#include <string>
#include <vector>

namespace mcval {

/// Linear RGB pixels, row by row from the top, three floats each.
struct RgbImage {
    int width = 0, height = 0;
    std::vector<float> rgb;
    const float *at(int x, int y) const { return rgb.data() + 3 * (size_t(y) * size_t(width) + size_t(x)); }
};

/// The largest image read, in pixels: 2^26 (a 16k x 4k environment map).
constexpr size_t kMaxImagePixels = size_t(1) << 26;

/// The R, G and B channels of `path` (a luminance-only Y channel as gray), half or float, as Mitsuba reads them:
/// linear, untouched. Throws std::runtime_error saying what is wrong: no such file, not an OpenEXR file, no colour
/// channel, larger than kMaxImagePixels.
RgbImage readExrRgb(const std::string &path);

}  // namespace mcval
