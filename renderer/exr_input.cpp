#include "exr_input.h"

#include <stdexcept>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

namespace mcval {

RgbImage readExrRgb(const std::string &path) {
    RgbImage image;
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const int64_t width = int64_t(window.max.x) - window.min.x + 1, height = int64_t(window.max.y) - window.min.y + 1;
        if (width <= 0 || height <= 0 || size_t(width) * size_t(height) > kMaxImagePixels)
            throw std::runtime_error("an image of " + std::to_string(width) + " x " + std::to_string(height) +
                                     " pixels (at most " + std::to_string(kMaxImagePixels) + " are read)");
        const Imf::ChannelList &channels = file.header().channels();
        const bool rgb = channels.findChannel("R") && channels.findChannel("G") && channels.findChannel("B");
        if (!rgb && !channels.findChannel("Y"))
            throw std::runtime_error("no R, G and B channels nor a Y channel (a layered or spectral image is not read)");
        image.width = int(width);
        image.height = int(height);
        image.rgb.assign(size_t(width) * size_t(height) * 3, 0.f);
        Imf::FrameBuffer fb;
        static const char *names[3] = {"R", "G", "B"};
        for (int c = 0; c < (rgb ? 3 : 1); ++c)
            fb.insert(rgb ? names[c] : "Y", Imf::Slice::Make(Imf::FLOAT, image.rgb.data() + c, window,
                                                             3 * sizeof(float), 3 * sizeof(float) * size_t(width)));
        file.setFrameBuffer(fb);
        file.readPixels(window.min.y, window.max.y);
        if (!rgb)
            for (size_t i = 0; i < image.rgb.size(); i += 3) image.rgb[i + 1] = image.rgb[i + 2] = image.rgb[i];
    } catch (const std::exception &e) {
        throw std::runtime_error(path + ": " + e.what());
    }
    return image;
}

}  // namespace mcval
