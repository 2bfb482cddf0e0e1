#include "render.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "camera.h"
#include "embree_scene.h"
#include "error.h"
#include "film.h"
#include "hot.h"
#include "integrators/integrator.h"
#include "scene_limits.h"
#include "worker_warmth.h"

namespace mcval {

namespace {

constexpr int kTileSize = 16;

struct Tile {
    int x0, y0, width, height;
};

/// The tiles of the pixels sampled, in film pixels: the film's crop window (the whole film unless the scene
/// crops it), and with sample_border a band around it as wide as the filter's border (Mitsuba's).
std::vector<Tile> makeTiles(const FilmSpec &film) {
    std::vector<Tile> tiles;
    const int border = film.sampleBorder ? static_cast<int>(std::ceil(film.filter.radius() - 0.5f)) : 0;
    const int x0 = film.cropX - border, y0 = film.cropY - border;
    const int x1 = film.cropX + film.cropWidth + border, y1 = film.cropY + film.cropHeight + border;
    for (int y = y0; y < y1; y += kTileSize)
        for (int x = x0; x < x1; x += kTileSize)
            tiles.push_back({x, y, std::min(kTileSize, x1 - x), std::min(kTileSize, y1 - y)});
    return tiles;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Mean and variance of the mean over K batch images.
void combineBatches(const std::vector<Image> &batches, Image &mean, Image &variance) {
    const size_t n = batches[0].rgb.size();
    const double k = static_cast<double>(batches.size());
    for (size_t i = 0; i < n; ++i) {
        double sum = 0.0, sum2 = 0.0;
        for (const Image &b : batches) {
            sum += b.rgb[i];
            sum2 += static_cast<double>(b.rgb[i]) * b.rgb[i];
        }
        const double m = sum / k;
        mean.rgb[i] = static_cast<float>(m);
        variance.rgb[i] = static_cast<float>(std::max(0.0, sum2 - k * m * m) / (k - 1.0) / k);
    }
}

/// Throws if any value of the image is NaN or infinite: such a render is never returned.
void requireFinite(const Image &image, const std::string &what, const std::string &file) {
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        if (std::isfinite(image.rgb[i])) continue;
        const size_t pixel = i / 3;
        throw SceneError(file, 0, "the " + what + " has a non-finite value at pixel (" + std::to_string(pixel % image.width) +
                         ", " + std::to_string(pixel / image.width) +
                         "): the scene's magnitudes overflow float32 (a light almost touching a surface?)");
    }
}

/// What every tile of a render reads; shared by the threads, never written.
struct RenderContext {
    const Camera &camera;
    const EmbreeScene &embree;
    const Integrator &integrator;
    int width, height;  ///< the whole film's
    int spp;
    uint64_t seed;
    SamplerType sampler;

    /// The sampler's key of film pixel (x, y): its index for a pixel of the film (whatever the crop window),
    /// and past them, for the border pixels sample_border adds (at most 2^16 outside), one of their own.
    uint64_t pixelKey(int x, int y) const {
        if (x >= 0 && y >= 0 && x < width && y < height) return static_cast<uint64_t>(y) * width + x;
        return static_cast<uint64_t>(width) * height + (static_cast<uint64_t>(y + 65536) << 32) +
               static_cast<uint64_t>(x + 65536);
    }
};

/// Camera-ray packets traced as one Embree stream: the coherent-stream traversal takes several packets
/// of neighbouring rays through the BVH together, a fifth faster here than one packet at a time.
constexpr int kStreamPackets = 4;

/// One packet of a pixel's samples: lanes first .. first + count - 1 of pixel x.
struct PacketJob {
    int x;
    int first;
    int count;
};

/// Film positions of a job's lanes (every lane computed, branch-free, so that the loop runs in SIMD).
MCVAL_HOT void jitter(const Sampler &sampler, int x, int y, int first, float *filmX, float *filmY) {
    if (sampler.type() == SamplerType::Independent) {
        for (int i = 0; i < kPacketSize; ++i) {
            const Vec2f j = sampler.independent2D(static_cast<uint32_t>(first + i), 0);
            filmX[i] = static_cast<float>(x) + j.x;
            filmY[i] = static_cast<float>(y) + j.y;
        }
    } else {
        for (int i = 0; i < kPacketSize; ++i) {
            const Vec2f j = sampler.sample2D(static_cast<uint32_t>(first + i), 0);
            filmX[i] = static_cast<float>(x) + j.x;
            filmY[i] = static_cast<float>(y) + j.y;
        }
    }
}

/// The camera rays of one job's lanes (the unused ones left out of the trace).
MCVAL_HOT void cameraRays(const Camera &camera, const float *filmX, const float *filmY, int count, RayHitPacket &packet) {
    const Vec3f origin = camera.origin();
    const float nearClip = camera.nearClip(), farClip = camera.farClip();
    if (camera.orthographic()) {
        // Parallel rays from the near plane over Mitsuba's maxt, far_clip - near_clip.
        for (int i = 0; i < kPacketSize; ++i)
            packet.set(i, i < count, camera.orthographicOrigin(filmX[i], filmY[i]), camera.forward(), 0.f,
                       farClip - nearClip);
    } else {
        for (int i = 0; i < kPacketSize; ++i) {
            float length;
            const Vec3f d = camera.direction(filmX[i], filmY[i], length);
            packet.set(i, i < count, origin, d, nearClip * length, farClip * length);
        }
    }
}

/// The jobs of one row, at most kStreamPackets (pbrt's EvaluatePixelSample for a run of samples): their
/// camera rays traced as one stream, then each packet's hits handed to the integrator and splatted, in
/// job order (pixel by pixel, packet by packet), so the film adds the same values in the same order as
/// one packet at a time would.
MCVAL_HOT void renderJobs(const RenderContext &ctx, int batch, int y, const PacketJob *jobs, int n, RayHitPacket *camera,
                          HitPacket *lanes, ImageBlock &block, RayCounts &counts) {
    alignas(64) float filmX[kStreamPackets][kPacketSize], filmY[kStreamPackets][kPacketSize];
    int laneCounts[kStreamPackets] = {};
    for (int j = 0; j < n; ++j) {
        const Sampler sampler(ctx.sampler, ctx.seed, static_cast<uint64_t>(batch), ctx.pixelKey(jobs[j].x, y));
        jitter(sampler, jobs[j].x, y, jobs[j].first, filmX[j], filmY[j]);
        cameraRays(ctx.camera, filmX[j], filmY[j], jobs[j].count, camera[j]);
        laneCounts[j] = jobs[j].count;
        counts.camera += static_cast<uint64_t>(jobs[j].count);
    }
    ctx.embree.intersect(camera, laneCounts, n, lanes);
    for (int j = 0; j < n; ++j) {
        Sampler sampler(ctx.sampler, ctx.seed, static_cast<uint64_t>(batch), ctx.pixelKey(jobs[j].x, y));
        Color radiance[kPacketSize];
        ctx.integrator.LiPacket({jobs[j].count, static_cast<uint32_t>(jobs[j].first), lanes[j]}, sampler, radiance, counts);
        block.putPacket(jobs[j].x, y, filmX[j], filmY[j], radiance, jobs[j].count);
    }
}

/// One tile of one batch (Nori's renderBlock): each row's pixels, their samples kPacketSize at a time
/// (the samples of one pixel are coherent), kStreamPackets packets to a stream.
void renderTile(const RenderContext &ctx, int batch, const Tile &tile, ImageBlock &block, RayCounts &counts) {
    PacketJob jobs[kStreamPackets];
    RayHitPacket camera[kStreamPackets];  // their fixed fields set once
    HitPacket lanes[kStreamPackets];
    for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
        int n = 0;
        for (int x = tile.x0; x < tile.x0 + tile.width; ++x)
            for (int first = 0; first < ctx.spp; first += kPacketSize) {
                jobs[n++] = {x, first, std::min(kPacketSize, ctx.spp - first)};
                if (n == kStreamPackets) {
                    renderJobs(ctx, batch, y, jobs, n, camera, lanes, block, counts);
                    n = 0;
                }
            }
        if (n > 0) renderJobs(ctx, batch, y, jobs, n, camera, lanes, block, counts);
    }
}

/// Tiles finished so far, reported one call at a time from the worker threads.
struct Progress {
    const std::function<void(double)> &report;
    size_t total;
    std::atomic<size_t> done{0};
    std::mutex mutex{};

    void tileDone() {
        const size_t finished = ++done;
        if (!report) return;
        std::lock_guard<std::mutex> lock(mutex);
        report(static_cast<double>(finished) / static_cast<double>(total));
    }
};

/// One batch image: its tiles in parallel, merged in a fixed order so that the bits do not depend
/// on the thread count; `mean` and `variance` are the film's per-pixel estimate and its variance.
void renderBatch(const RenderContext &ctx, int batch, const std::vector<Tile> &tiles, const FilmSpec &spec,
                 tbb::enumerable_thread_specific<RayCounts> &counts, Progress &progress, Image &mean, Image &variance) {
    std::vector<ImageBlock> blocks;
    blocks.reserve(tiles.size());
    for (const Tile &t : tiles) blocks.emplace_back(t.x0, t.y0, t.width, t.height, spec.filter);
    tbb::parallel_for(size_t(0), tiles.size(), [&](size_t ti) {
        renderTile(ctx, batch, tiles[ti], blocks[ti], counts.local());
        progress.tileDone();
    });
    Film film(mean.width, mean.height, spec.cropX, spec.cropY);
    for (const ImageBlock &block : blocks) film.merge(block);
    film.develop(mean.rgb, variance.rgb);
}

/// Throws unless the film, its batches and the sample count fit the renderer's limits.
void requireWithinLimits(const SceneDescription &scene, int spp, int batches) {
    if (spp > kMaxSampleCount) throw SceneError("spp must be at most " + std::to_string(kMaxSampleCount));
    if (batches > kMaxBatches) throw SceneError("batches must be at most " + std::to_string(kMaxBatches));
    // Film sums (11 doubles) and the mean, variance and batch images (3 floats each) per pixel.
    const double bytes = double(scene.film.cropWidth) * scene.film.cropHeight * (11 * 8 + 12 * (2 + batches));
    if (bytes > kMaxImageBytes)
        throw SceneError(scene.file, 0, "a " + std::to_string(scene.film.cropWidth) + "x" + std::to_string(scene.film.cropHeight) +
                                            " film with " + std::to_string(batches) + " batches needs " +
                                            std::to_string(int(bytes / (1 << 20))) + " MiB; the limit is " +
                                            std::to_string(int(kMaxImageBytes / (1 << 20))) + " MiB");
}

}  // namespace

RenderOutput render(const SceneDescription &scene, const RenderOptions &options) {
    // A different integrator than the scene's runs with its own defaults, not the scene's parameters.
    IntegratorSpec spec = scene.integrator;
    if (!options.integrator.empty() && options.integrator != spec.type) spec = {options.integrator, {}};
    const int spp = options.spp > 0 ? options.spp : scene.sampleCount;
    SamplerType sampler = scene.sampler;
    if (!options.sampler.empty()) {
        const auto chosen = parseSampler(options.sampler);
        if (!chosen) throw SceneError("unknown sampler \"" + options.sampler + "\": expected independent or sobol");
        sampler = *chosen;
    }
    const int batches = std::max(1, options.batches);
    requireWithinLimits(scene, spp, batches);
    // The camera projects onto the whole film; the image is its crop window.
    const int width = scene.film.cropWidth, height = scene.film.cropHeight;

    std::unique_ptr<tbb::global_control> limit;
    if (options.threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

    RenderOutput out;
    out.stats.spp = spp;
    out.stats.batches = batches;
    out.stats.seed = options.seed;
    out.stats.integrator = spec.type;
    out.stats.sampler = samplerName(sampler);

    workersStart();
    auto start = std::chrono::steady_clock::now();
    const EmbreeScene embree(scene.meshes, scene.spheres, scene.disks, scene.cylinders, scene.bsdfs);
    const auto integrator = createIntegrator(spec, scene, embree);  // validates the name before any work
    out.stats.bvhSeconds = secondsSince(start);

    const Camera camera(scene.camera, scene.film.width, scene.film.height);
    const RenderContext ctx{camera, embree, *integrator, scene.film.width, scene.film.height, spp, options.seed, sampler};
    const std::vector<Tile> tiles = makeTiles(scene.film);
    tbb::enumerable_thread_specific<RayCounts> counts;
    Progress progress{options.progress, tiles.size() * batches};

    start = std::chrono::steady_clock::now();
    for (int b = 0; b < batches; ++b) {
        Image mean{width, height, {}}, variance{width, height, {}};
        renderBatch(ctx, b, tiles, scene.film, counts, progress, mean, variance);
        if (batches == 1) {
            out.mean = std::move(mean);
            out.variance = std::move(variance);
        } else {
            out.batches.push_back(std::move(mean));
        }
    }
    if (batches > 1) {
        out.mean = {width, height, std::vector<float>(3 * size_t(width) * height)};
        out.variance = out.mean;
        combineBatches(out.batches, out.mean, out.variance);
    }
    requireFinite(out.mean, "image", scene.file);
    requireFinite(out.variance, "variance image", scene.file);
    for (size_t k = 0; k < out.batches.size(); ++k)
        requireFinite(out.batches[k], "batch " + std::to_string(k), scene.file);
    out.stats.renderSeconds = secondsSince(start);
    if (options.keepWarmMilliseconds > 0) keepWorkersWarm(options.keepWarmMilliseconds);
    for (const RayCounts &c : counts) {
        out.stats.cameraRays += c.camera;
        out.stats.shadowRays += c.shadow;
    }
    return out;
}

}  // namespace mcval
