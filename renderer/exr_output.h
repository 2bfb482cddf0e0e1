// OpenEXR output: linear float32 mean, variance and batch layers, timings in the header.
#pragma once

#include <functional>
#include <string>

#include "render.h"

namespace mcval {

/// Timings measured outside render() (scene loading), to go into the header beside the rest.
struct OutputInfo {
    std::string sceneFile;
    double loadSeconds = 0.0;
    bool half = false;  ///< the film's component_format is float16: write HALF channels
};

/// Writes R, G, B (mean), variance.R/G/B and, for K > 1 batches, batch<k>.R/G/B. Header attributes
/// mcval.* hold the integrator, spp, seed, timings and ray counts. Written to a temporary file in
/// the same folder, then renamed: a reader never sees half a file.
/// Throws SceneError (and leaves no temporary file) if the path cannot take the image.
void writeExr(const std::string &path, const RenderOutput &output, const OutputInfo &info);

/// Calls write(tmp) with a temporary path beside `path`, then renames it to `path`: a reader never sees half a
/// file. Throws SceneError (and leaves no temporary file) if the path cannot take it or `write` throws.
void writeAtomically(const std::string &path, const std::function<void(const std::string &)> &write);

/// Throws SceneError unless `path` names a regular file or nothing, in an existing folder: the
/// output never replaces a folder, FIFO or device.
void requireWritableOutput(const std::string &path);

}  // namespace mcval
