// The C interface of libmcval_imageio, the one part of the renderer that links OpenImageIO: the renderer loads
// it (texture_loader.cpp) only when a scene holds a bitmap, so that every other run starts without OpenImageIO's
// two hundred shared libraries.
#pragma once

#include <cstddef>

extern "C" {

/// An image file's pixels as floats (integer formats scaled to [0, 1]), row by row from the top.
struct McvalImageFile {
    int width, height, channels;
    int integer;      ///< stored as 8- or 16-bit integers (PNG, JPEG, BMP, TGA): Mitsuba reads those as sRGB
    int bytesPerChannel;
    float *pixels;    ///< width * height * channels floats, for mcval_free_image_file
};

/// Reads `path`; 0 on success, else -1 with a message in `error` (at most errorSize bytes, terminated). At most
/// maxPixels pixels and 4 channels are read.
int mcval_read_image_file(const char *path, size_t maxPixels, McvalImageFile *out, char *error, size_t errorSize);
void mcval_free_image_file(McvalImageFile *image);

}
