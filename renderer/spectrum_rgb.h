// A spectrum given per wavelength ("400:0.2, 500:0.4, ...") turned into linear sRGB as Mitsuba 3's RGB variants
// turn it when they load a scene (spectrum_list_to_srgb): the piecewise-linear spectrum integrated against the
// CIE 1931 matching functions (weighted by D65 for a reflectance), to XYZ, to sRGB.
#pragma once

#include <vector>

#include "vector.h"

namespace mcval {

/// How Mitsuba's loader converts a spectrum: inside an <emitter> as light (no illuminant, negative channels 0),
/// elsewhere as a reflectance (under D65, channels clamped to [0, 1]).
enum class SpectrumUse { Emission, Reflectance };

/// The sRGB colour of the spectrum of `values` at increasing `wavelengths` (nm), zero outside them.
Vec3f spectrumToRgb(const std::vector<float> &wavelengths, const std::vector<float> &values, SpectrumUse use);

}  // namespace mcval
