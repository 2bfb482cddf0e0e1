// Raw output for a reader on the same machine that reads the file at once (the harness's render worker):
// the images as float32 rows, no encoding, after one header line.
#pragma once

#include <string>

#include "exr_output.h"
#include "render.h"

namespace mcval {

/// Writes one line "mcval-raw 1 WIDTH HEIGHT IMAGES load=S bvh=S render=S sampler=NAME\n", then IMAGES images
/// of HEIGHT x WIDTH x 3 little-endian float32 (row-major from the top-left pixel): the K batches, or the mean
/// when there is one batch. Written atomically (see writeAtomically); throws SceneError as writeExr does.
void writeRaw(const std::string &path, const RenderOutput &output, const OutputInfo &info);

}  // namespace mcval
