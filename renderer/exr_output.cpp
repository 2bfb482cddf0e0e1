#include "exr_output.h"

#include <cstdio>
#include <deque>
#include <filesystem>
#include <random>

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <half.h>

#include "error.h"

namespace mcval {

namespace {

/// Adds R, G, B of `image`; as HALF channels (converted into `halves`, which must outlive the write) if `half`.
void addLayer(Imf::Header &header, Imf::FrameBuffer &fb, const std::string &prefix, const Image &image,
              bool half, std::deque<std::vector<::half>> &halves) {
    static const char *names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
        const std::string name = prefix + names[c];
        if (half) {
            std::vector<::half> &h = halves.emplace_back(image.rgb.size() / 3);
            for (size_t i = 0; i < h.size(); ++i) h[i] = ::half(image.rgb[3 * i + c]);
            header.channels().insert(name, Imf::Channel(Imf::HALF));
            fb.insert(name, Imf::Slice(Imf::HALF, reinterpret_cast<char *>(h.data()), sizeof(::half),
                                       sizeof(::half) * image.width));
        } else {
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            char *base = reinterpret_cast<char *>(const_cast<float *>(image.rgb.data() + c));
            fb.insert(name, Imf::Slice(Imf::FLOAT, base, 3 * sizeof(float), 3 * sizeof(float) * image.width));
        }
    }
}

}  // namespace

void writeExr(const std::string &path, const RenderOutput &output, const OutputInfo &info) {
    const RenderStats &s = output.stats;
    Imf::Header header(output.mean.width, output.mean.height);
    header.insert("mcval.scene", Imf::StringAttribute(info.sceneFile));
    header.insert("mcval.integrator", Imf::StringAttribute(s.integrator));
    header.insert("mcval.sampler", Imf::StringAttribute(s.sampler));
    header.insert("mcval.spp", Imf::IntAttribute(s.spp));
    header.insert("mcval.batches", Imf::IntAttribute(s.batches));
    header.insert("mcval.seed", Imf::StringAttribute(std::to_string(s.seed)));
    header.insert("mcval.loadSeconds", Imf::DoubleAttribute(info.loadSeconds));
    header.insert("mcval.bvhSeconds", Imf::DoubleAttribute(s.bvhSeconds));
    header.insert("mcval.renderSeconds", Imf::DoubleAttribute(s.renderSeconds));
    header.insert("mcval.cameraRays", Imf::StringAttribute(std::to_string(s.cameraRays)));
    header.insert("mcval.shadowRays", Imf::StringAttribute(std::to_string(s.shadowRays)));

    Imf::FrameBuffer fb;
    std::deque<std::vector<::half>> halves;
    addLayer(header, fb, "", output.mean, info.half, halves);
    addLayer(header, fb, "variance.", output.variance, info.half, halves);
    for (size_t k = 0; k < output.batches.size(); ++k)
        addLayer(header, fb, "batch" + std::to_string(k) + ".", output.batches[k], info.half, halves);

    writeAtomically(path, [&](const std::string &tmp) {
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(output.mean.height);
    });
}

void writeAtomically(const std::string &path, const std::function<void(const std::string &)> &write) {
    requireWritableOutput(path);
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path tmp = target.parent_path() /
                         ("." + target.filename().string() + ".tmp" + std::to_string(std::random_device{}()));
    try {
        write(tmp.string());
        requireWritableOutput(path);  // still a regular file (or nothing) just before the rename
        std::error_code ec;
        fs::rename(tmp, target, ec);
        if (ec) throw SceneError(path, 0, "cannot write the output: " + ec.message());
    } catch (const SceneError &) {
        std::remove(tmp.string().c_str());
        throw;
    } catch (const std::exception &e) {
        std::remove(tmp.string().c_str());
        throw SceneError(path, 0, std::string("cannot write the output: ") + e.what());
    }
}

void requireWritableOutput(const std::string &path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path target(path);
    const fs::file_status status = fs::status(target, ec);
    if (ec && status.type() != fs::file_type::not_found)
        throw SceneError(path, 0, "cannot use as output: " + ec.message());
    if (fs::exists(status) && !fs::is_regular_file(status))
        throw SceneError(path, 0, "output exists and is not a regular file (a folder, FIFO or device?)");
    const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    if (!fs::is_directory(parent, ec)) throw SceneError(path, 0, "the output's folder does not exist");
}

}  // namespace mcval
