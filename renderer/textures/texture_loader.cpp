#include "texture_loader.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include <dlfcn.h>
#include <half.h>

#include "image_file.h"

namespace mcval {

namespace {

/// Mitsuba's sRGB to linear conversion of a value in [0, 1].
float srgbToLinear(float v) {
    return v <= 0.04045f ? v * (1.f / 12.92f) : std::pow((v + 0.055f) * (1.f / 1.055f), 2.4f);
}

/// libmcval_imageio's two functions, loaded on first use: where the build put it, else beside the program.
struct ImageFileReader {
    decltype(&mcval_read_image_file) read = nullptr;
    decltype(&mcval_free_image_file) free = nullptr;
    std::string error;  ///< why it could not be loaded
};

const ImageFileReader &imageFileReader() {
    static const ImageFileReader reader = [] {
        ImageFileReader r;
        void *library = dlopen(MCVAL_IMAGEIO_LIBRARY, RTLD_NOW | RTLD_LOCAL);
        if (!library) {
            r.error = dlerror();
            std::error_code ec;
            const auto beside = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() /
                                std::filesystem::path(MCVAL_IMAGEIO_LIBRARY).filename();
            library = dlopen(beside.c_str(), RTLD_NOW | RTLD_LOCAL);
        }
        if (!library) return r;
        r.read = reinterpret_cast<decltype(r.read)>(dlsym(library, "mcval_read_image_file"));
        r.free = reinterpret_cast<decltype(r.free)>(dlsym(library, "mcval_free_image_file"));
        return r;
    }();
    if (!reader.read || !reader.free)
        throw std::runtime_error(std::string("cannot load the image reader ") + MCVAL_IMAGEIO_LIBRARY +
                                 " (built with the renderer; it links OpenImageIO): " + reader.error);
    return reader;
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
    std::shared_ptr<const RgbImage> image;
    try {
        image = std::make_shared<const RgbImage>(readRgbImage(ctx.resolve(name), raw));
    } catch (const std::exception &e) {
        props.failAt("filename", std::string("cannot read the texture's image: ") + e.what());
    }
    if (const std::string where = badPixel(*image, maxValue); !where.empty())
        props.failAt("filename", "the image's pixel" + where + " holds a value outside [0, " +
                                     std::to_string(maxValue) + "], which a reflectance cannot be");
    return std::make_shared<const BitmapTexture>(image, wrap, filter, toUv);
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

RgbImage readRgbImage(const std::string &path, bool raw) {
    const ImageFileReader &reader = imageFileReader();
    McvalImageFile file{};
    char error[512];
    if (reader.read(path.c_str(), kMaxImagePixels, &file, error, sizeof(error)) != 0)
        throw std::runtime_error(path + ": " + error);
    std::unique_ptr<McvalImageFile, void (*)(McvalImageFile *)> owned(&file, reader.free);
    // Mitsuba reads integer images (PNG, JPEG, BMP, TGA) as sRGB and stores every image of at most 16 bits a
    // channel in half precision; float images (OpenEXR, RGBE, PFM) are linear.
    const bool storedHalf = file.bytesPerChannel <= 2;
    const size_t pixels = size_t(file.width) * size_t(file.height), channels = size_t(file.channels);
    RgbImage image;
    image.width = file.width;
    image.height = file.height;
    image.rgb.resize(pixels * 3);
    const bool colour = channels >= 3;  // YA's A and RGBA's A are dropped
    for (size_t i = 0; i < pixels; ++i)
        for (size_t c = 0; c < 3; ++c) {
            float v = file.pixels[i * channels + (colour ? c : 0)];
            if (file.integer && !raw) v = srgbToLinear(v);
            if (storedHalf) v = float(::half(v));
            image.rgb[3 * i + c] = v;
        }
    return image;
}

std::string badPixel(const RgbImage &image, float maxValue) {
    for (size_t i = 0; i < image.rgb.size(); ++i)
        if (!(image.rgb[i] >= 0.f && image.rgb[i] <= maxValue)) {
            const size_t pixel = i / 3;
            return " (" + std::to_string(pixel % size_t(image.width)) + ", " +
                   std::to_string(pixel / size_t(image.width)) + ")";
        }
    return "";
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
