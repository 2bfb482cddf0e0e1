#include "image_file.h"

#include <cstdlib>
#include <cstring>
#include <string>

#include <OpenImageIO/imageio.h>

namespace {

int fail(const std::string &message, char *error, size_t errorSize) {
    if (errorSize > 0) {
        std::strncpy(error, message.c_str(), errorSize - 1);
        error[errorSize - 1] = '\0';
    }
    return -1;
}

}  // namespace

extern "C" int mcval_read_image_file(const char *path, size_t maxPixels, McvalImageFile *out, char *error,
                                     size_t errorSize) {
    try {
        auto in = OIIO::ImageInput::open(path);
        if (!in) return fail(OIIO::geterror(), error, errorSize);
        const OIIO::ImageSpec spec = in->spec();
        const long long width = spec.width, height = spec.height;
        if (width <= 0 || height <= 0 || size_t(width) * size_t(height) > maxPixels)
            return fail("an image of " + std::to_string(width) + " x " + std::to_string(height) + " pixels (at most " +
                            std::to_string(maxPixels) + " are read)",
                        error, errorSize);
        if (spec.nchannels < 1 || spec.nchannels > 4)
            return fail(std::to_string(spec.nchannels) + " channels (Y, YA, RGB or RGBA are read)", error, errorSize);
        const size_t count = size_t(width) * size_t(height) * size_t(spec.nchannels);
        auto *pixels = static_cast<float *>(std::malloc(count * sizeof(float)));
        if (!pixels) return fail("out of memory", error, errorSize);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels)) {
            std::free(pixels);
            return fail(in->geterror(), error, errorSize);
        }
        out->width = int(width);
        out->height = int(height);
        out->channels = spec.nchannels;
        out->integer = spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
        out->bytesPerChannel = int(spec.format.size());
        out->pixels = pixels;
        return 0;
    } catch (const std::exception &e) {
        return fail(e.what(), error, errorSize);
    }
}

extern "C" void mcval_free_image_file(McvalImageFile *image) {
    std::free(image->pixels);
    image->pixels = nullptr;
}
