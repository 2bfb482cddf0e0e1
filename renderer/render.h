// Rendering a loaded scene: tiles over all cores, K independent batches, timings and ray counts.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "scene.h"

namespace mcval {

struct RenderOptions {
    int spp = 0;                 ///< samples per pixel per batch; 0: the scene's sample_count
    uint64_t seed = 0;
    int threads = 0;             ///< 0: all cores
    int batches = 1;             ///< independent images, each with spp samples per pixel
    std::string integrator;      ///< overrides the scene's <integrator> when not empty
    std::string sampler;         ///< overrides the scene's <sampler> when not empty: independent or sobol
    /// Called with the fraction done (0..1), from worker threads, one call at a time.
    std::function<void(double)> progress;
    /// Milliseconds a worker thread keeps spinning after the render, for a caller that renders again
    /// soon (the Python module); 0 lets it sleep at once (the command line, which exits).
    int keepWarmMilliseconds = 0;
};

/// An RGB float image, row-major from the top-left pixel.
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;
};

struct RenderStats {
    double bvhSeconds = 0.0, renderSeconds = 0.0;
    uint64_t cameraRays = 0, shadowRays = 0;
    int spp = 0, batches = 1;
    uint64_t seed = 0;
    std::string integrator;
    std::string sampler;
};

struct RenderOutput {
    Image mean;       ///< the estimate (over all batches)
    Image variance;   ///< variance of that estimate per pixel and channel
    std::vector<Image> batches;  ///< the K batch images when batches > 1
    RenderStats stats;
};

/// Renders `scene`; the result depends only on the scene and the options, never on the thread count.
RenderOutput render(const SceneDescription &scene, const RenderOptions &options);

}  // namespace mcval
