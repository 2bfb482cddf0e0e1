#include "raw_output.h"

#include <cstdio>
#include <memory>
#include <vector>

#include "error.h"

namespace mcval {

void writeRaw(const std::string &path, const RenderOutput &output, const OutputInfo &info) {
    std::vector<const Image *> images;
    for (const Image &b : output.batches) images.push_back(&b);
    if (images.empty()) images.push_back(&output.mean);
    const RenderStats &s = output.stats;
    writeAtomically(path, [&](const std::string &tmp) {
        const std::unique_ptr<FILE, int (*)(FILE *)> file(std::fopen(tmp.c_str(), "wb"), std::fclose);
        if (!file) throw SceneError(path, 0, "cannot open the output for writing");
        std::fprintf(file.get(), "mcval-raw 1 %d %d %zu load=%.9g bvh=%.9g render=%.9g sampler=%s\n", output.mean.width,
                     output.mean.height, images.size(), info.loadSeconds, s.bvhSeconds, s.renderSeconds, s.sampler.c_str());
        for (const Image *image : images)
            if (std::fwrite(image->rgb.data(), sizeof(float), image->rgb.size(), file.get()) != image->rgb.size())
                throw SceneError(path, 0, "cannot write the output (disk full?)");
        if (std::fflush(file.get()) != 0) throw SceneError(path, 0, "cannot write the output (disk full?)");
    });
}

}  // namespace mcval
