// The <texture> elements a diffuse reflectance may be given: Mitsuba's `bitmap` (an image file read with
// OpenImageIO) and `checkerboard`, with Mitsuba's parameter names and defaults.
#pragma once

#include <memory>
#include <string>

#include <pugixml.hpp>

#include "../xml_props.h"
#include "texture.h"

namespace mcval {

/// Whether this renderer reads a <texture type="...">.
inline bool isModelledTexture(const std::string &type) { return type == "bitmap" || type == "checkerboard"; }

/// A <texture type="bitmap|checkerboard"> element. Throws SceneError at its line (or its property's): an image
/// that cannot be read, an unknown wrap_mode or filter_type, a value outside [0, maxValue].
std::shared_ptr<const Texture> loadTexture(const XmlContext &ctx, const pugi::xml_node &node, float maxValue);

/// The largest image read, in pixels: 2^26 (a 16k x 4k environment map).
constexpr size_t kMaxImagePixels = size_t(1) << 26;

/// An image file as Mitsuba's bitmap texture reads it: 8- and 16-bit images taken from sRGB to linear (unless
/// raw), then, as Mitsuba stores them, rounded to half precision; float images as they are. Throws
/// std::runtime_error saying what is wrong.
RgbImage readRgbImage(const std::string &path, bool raw);

/// The first pixel with a value outside [0, maxValue] or not finite, as " (x, y)"; "" if there is none.
std::string badPixel(const RgbImage &image, float maxValue);

}  // namespace mcval
