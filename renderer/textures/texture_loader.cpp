#include "texture_loader.h"

#include <cmath>
#include <stdexcept>

#include <OpenImageIO/imageio.h>
#include <half.h>

#include "../exr_input.h"

namespace mcval {

namespace {

/// Mitsuba's sRGB to linear conversion of a value in [0, 1].
float srgbToLinear(float v) {
    return v <= 0.04045f ? v * (1.f / 12.92f) : std::pow((v + 0.055f) * (1.f / 1.055f), 2.4f);
}

std::shared_ptr<const Texture> loadBitmap(const XmlContext &ctx, XmlProps &props, float maxValue) {
    const std::string name = props.getStringRequired("filename");
    const bool raw = props.getBool("raw", false);
    const std::string wrapName = props.getString("wrap_mode", "repeat");
    WrapMode wrap = WrapMode::Repeat;
    if (wrapName == "mirror") wrap = WrapMode::Mirror;
    else if (wrapName == "clamp") wrap = WrapMode::Clamp;
    else if (wrapName != "repeat") props.failAt("wrap_mode", "expected repeat, mirror or clamp, not \"" + wrapName + "\"");
    const std::string filterName = props.getString("filter_type", "bilinear");
    FilterMode filter = FilterMode::Bilinear;
    if (filterName == "nearest") filter = FilterMode::Nearest;
    else if (filterName != "bilinear")
        props.failAt("filter_type", "expected bilinear or nearest, not \"" + filterName + "\"");
    const UvTransform toUv(props.getTransform("to_uv"));
    // Storage and acceleration choices that leave the values as they are (format fp16 is the default's).
    props.ignore("accel");
    const std::string format = props.getString("format", "auto");
    if (format != "auto" && format != "fp16" && format != "variant")
        props.failAt("format", "expected auto, variant or fp16, not \"" + format + "\"");
    props.finish("filename, raw, wrap_mode, filter_type, to_uv, format, accel");
    std::shared_ptr<const TextureImage> image;
    try {
        image = std::make_shared<const TextureImage>(readTextureImage(ctx.resolve(name), raw));
    } catch (const std::exception &e) {
        props.failAt("filename", std::string("cannot read the texture's image: ") + e.what());
    }
    auto texture = std::make_shared<const BitmapTexture>(image, wrap, filter, toUv);
    for (float v : image->rgb)
        if (!(v >= 0.f && v <= maxValue))
            props.failAt("filename", "the image holds a value outside [0, " + std::to_string(maxValue) +
                                         "], which a reflectance cannot be");
    return texture;
}

std::shared_ptr<const Texture> loadCheckerboard(XmlProps &props, float maxValue) {
    // Mitsuba's defaults.
    const Color color0 = props.getColor("color0", {0.4f, 0.4f, 0.4f});
    const Color color1 = props.getColor("color1", {0.2f, 0.2f, 0.2f});
    props.requireRange("color0", color0, 0.f, maxValue);
    props.requireRange("color1", color1, 0.f, maxValue);
    const UvTransform toUv(props.getTransform("to_uv"));
    props.finish("color0, color1, to_uv");
    return std::make_shared<const CheckerboardTexture>(color0, color1, toUv);
}

}  // namespace

TextureImage readTextureImage(const std::string &path, bool raw) {
    auto in = OIIO::ImageInput::open(path);
    if (!in) throw std::runtime_error(path + ": " + OIIO::geterror());
    const OIIO::ImageSpec spec = in->spec();
    const int64_t width = spec.width, height = spec.height;
    const int channels = spec.nchannels;
    if (width <= 0 || height <= 0 || size_t(width) * size_t(height) > kMaxImagePixels)
        throw std::runtime_error(path + ": an image of " + std::to_string(width) + " x " + std::to_string(height) +
                                 " pixels (at most " + std::to_string(kMaxImagePixels) + " are read)");
    if (channels < 1 || channels > 4)
        throw std::runtime_error(path + ": " + std::to_string(channels) + " channels (Y, YA, RGB or RGBA are read)");
    std::vector<float> pixels(size_t(width) * size_t(height) * size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels.data()))
        throw std::runtime_error(path + ": " + in->geterror());
    // Mitsuba reads integer images (PNG, JPEG, BMP, TGA) as sRGB and stores every image of at most 16 bits a
    // channel in half precision; float images (OpenEXR, RGBE, PFM) are linear.
    const bool integer = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
    const bool storedHalf = spec.format.size() <= 2;
    TextureImage image;
    image.width = int(width);
    image.height = int(height);
    image.rgb.resize(size_t(width) * size_t(height) * 3);
    const int colour = channels >= 3 ? 3 : 1;  // YA's A and RGBA's A are dropped
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (int c = 0; c < 3; ++c) {
            float v = pixels[i * size_t(channels) + size_t(colour == 3 ? c : 0)];
            if (integer && !raw) v = srgbToLinear(v);
            if (storedHalf) v = float(::half(v));
            image.rgb[3 * i + size_t(c)] = v;
        }
    return image;
}

std::shared_ptr<const Texture> loadTexture(const XmlContext &ctx, const pugi::xml_node &node, float maxValue) {
    const std::string type = ctx.attr(node, "type");
    XmlProps props(ctx, node);
    if (!props.objects().empty())
        ctx.fail(props.objects()[0], "a texture inside a texture is not modelled: give color0 and color1 as values");
    if (type == "bitmap") return loadBitmap(ctx, props, maxValue);
    if (type == "checkerboard") return loadCheckerboard(props, maxValue);
    ctx.fail(node, "unsupported texture type \"" + type + "\": expected bitmap or checkerboard");
}

}  // namespace mcval
