// The `render` command: one invocation's arguments to one EXR, for the command line and for --serve.
#pragma once

#include <string>
#include <vector>

namespace mcval {

/// Runs `render ARGS...` (without the program name) and returns its exit status: 0 when the image was
/// written, 1 for bad input (the scene, an option's value), 2 for any other error, and CLI11's status for
/// arguments it cannot parse. Messages go to stderr as one line; --help to stdout. `keepWarmMilliseconds`: how
/// long a worker thread spins after the render, for a caller that renders again soon (see worker_warmth.h).
int runRenderCommand(const std::vector<std::string> &args, int keepWarmMilliseconds = 0);

}  // namespace mcval
