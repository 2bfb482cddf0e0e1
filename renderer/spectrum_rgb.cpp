#include "spectrum_rgb.h"

#include <algorithm>
#include <array>
#include <limits>

namespace mcval {

namespace {

constexpr int kCieMin = 360, kCieMax = 830;
/// Mitsuba's MI_CIE_Y_NORMALIZATION: 1 / the integral of the CIE y function.
constexpr double kCieYNormalization = 0.009367658735689113;
/// The points the spectrum is read at between kCieMin and kCieMax (Mitsuba's).
constexpr int kSteps = 1000;

/// x, y, z and D65 (normalised) at each nanometre from kCieMin to kCieMax.
constexpr std::array<std::array<float, 4>, kCieMax - kCieMin + 1> kTables = {{
#include "spectrum_tables.inc"
}};

/// The tables at `nm`, interpolated linearly between whole nanometres.
std::array<double, 4> tablesAt(double nm) {
    const double t = std::clamp(nm - kCieMin, 0.0, double(kCieMax - kCieMin));
    const int i = std::min(int(t), kCieMax - kCieMin - 1);
    const double f = t - i;
    std::array<double, 4> out;
    for (int k = 0; k < 4; ++k) out[k] = (1.0 - f) * kTables[i][k] + f * kTables[i + 1][k];
    return out;
}

}  // namespace

Vec3f spectrumToRgb(const std::vector<float> &wavelengths, const std::vector<float> &values, SpectrumUse use) {
    double x = 0.0, y = 0.0, z = 0.0;
    for (int step = 0; step < kSteps; ++step) {
        const double nm = kCieMin + (double(step) / (kSteps - 1)) * (kCieMax - kCieMin);
        if (nm < wavelengths.front() || nm > wavelengths.back()) continue;
        const size_t hi = std::min(size_t(std::upper_bound(wavelengths.begin(), wavelengths.end(), float(nm)) -
                                          wavelengths.begin()), wavelengths.size() - 1);
        const size_t lo = hi == 0 ? 0 : hi - 1;
        const double span = double(wavelengths[hi]) - wavelengths[lo];
        const double f = span > 0.0 ? (nm - wavelengths[lo]) / span : 0.0;
        double v = (1.0 - f) * values[lo] + f * values[hi];
        const std::array<double, 4> t = tablesAt(nm);
        if (use == SpectrumUse::Reflectance) v *= t[3];
        x += t[0] * v, y += t[1] * v, z += t[2] * v;
    }
    const double scale = double(kCieMax - kCieMin) / kSteps * kCieYNormalization;
    x *= scale, y *= scale, z *= scale;
    // XYZ to linear sRGB (D65 white).
    Vec3f rgb(float(3.240479 * x - 1.537150 * y - 0.498535 * z), float(-0.969256 * x + 1.875991 * y + 0.041556 * z),
              float(0.055648 * x - 0.204043 * y + 1.057311 * z));
    // Out of the sRGB gamut: negative channels become 0, and a reflectance's channels at most 1 (Mitsuba's).
    const float top = use == SpectrumUse::Reflectance ? 1.f : std::numeric_limits<float>::infinity();
    return {std::clamp(rgb.x, 0.f, top), std::clamp(rgb.y, 0.f, top), std::clamp(rgb.z, 0.f, top)};
}

}  // namespace mcval
