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
#include "integrators/integrator.h"
#include "scene_limits.h"

namespace mcval {

namespace {

constexpr int kTileSize = 32;
constexpr int kPacket = 8;  ///< camera rays traced together

struct Tile {
    int x0, y0, width, height;
};

std::vector<Tile> makeTiles(int width, int height) {
    std::vector<Tile> tiles;
    for (int y = 0; y < height; y += kTileSize)
        for (int x = 0; x < width; x += kTileSize)
            tiles.push_back({x, y, std::min(kTileSize, width - x), std::min(kTileSize, height - y)});
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

}  // namespace

RenderOutput render(const SceneDescription &scene, const RenderOptions &options) {
    IntegratorSpec spec = scene.integrator;
    if (!options.integrator.empty()) spec.type = options.integrator;
    const int spp = options.spp > 0 ? options.spp : scene.sampleCount;
    const int batches = std::max(1, options.batches);
    if (spp > kMaxSampleCount) throw SceneError("spp must be at most " + std::to_string(kMaxSampleCount));
    if (batches > kMaxBatches) throw SceneError("batches must be at most " + std::to_string(kMaxBatches));
    // Film sums (11 doubles) and the mean, variance and batch images (3 floats each) per pixel.
    const double bytes = double(scene.film.width) * scene.film.height * (11 * 8 + 12 * (2 + batches));
    if (bytes > kMaxImageBytes)
        throw SceneError(scene.file, 0, "a " + std::to_string(scene.film.width) + "x" + std::to_string(scene.film.height) +
                                            " film with " + std::to_string(batches) + " batches needs " +
                                            std::to_string(int(bytes / (1 << 20))) + " MiB; the limit is " +
                                            std::to_string(int(kMaxImageBytes / (1 << 20))) + " MiB");
    const int width = scene.film.width, height = scene.film.height;

    std::unique_ptr<tbb::global_control> limit;
    if (options.threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, options.threads);

    RenderOutput out;
    out.stats.spp = spp;
    out.stats.batches = batches;
    out.stats.seed = options.seed;
    out.stats.integrator = spec.type;

    auto start = std::chrono::steady_clock::now();
    const EmbreeScene embree(scene.meshes);
    const auto integrator = createIntegrator(spec, scene, embree);  // validates the name before any work
    out.stats.bvhSeconds = secondsSince(start);

    const Camera camera(scene.camera, width, height);
    const std::vector<Tile> tiles = makeTiles(width, height);
    tbb::enumerable_thread_specific<RayCounts> counts;
    std::atomic<size_t> done{0};
    std::mutex progressMutex;
    const size_t totalWork = tiles.size() * batches;

    start = std::chrono::steady_clock::now();
    for (int b = 0; b < batches; ++b) {
        std::vector<ImageBlock> blocks;
        blocks.reserve(tiles.size());
        for (const Tile &t : tiles) blocks.emplace_back(t.x0, t.y0, t.width, t.height, scene.film.filter);
        tbb::parallel_for(size_t(0), tiles.size(), [&](size_t ti) {
            const Tile &tile = tiles[ti];
            RayCounts &local = counts.local();
            for (int y = tile.y0; y < tile.y0 + tile.height; ++y) {
                for (int x = tile.x0; x < tile.x0 + tile.width; ++x) {
                    Sampler sampler(options.seed, static_cast<uint64_t>(b), static_cast<uint64_t>(y) * width + x);
                    // The samples of one pixel are coherent: trace their camera rays 8 at a time.
                    for (int first = 0; first < spp; first += kPacket) {
                        const int count = std::min(kPacket, spp - first);
                        Ray rays[kPacket];
                        Vec2f film[kPacket];
                        for (int i = 0; i < count; ++i) {
                            sampler.startSample(static_cast<uint32_t>(first + i));
                            const Vec2f jitter = sampler.next2D();
                            film[i] = {static_cast<float>(x) + jitter.x, static_cast<float>(y) + jitter.y};
                            rays[i] = camera.generateRay(film[i].x, film[i].y);
                        }
                        Hit hits[kPacket];
                        bool found[kPacket];
                        embree.intersect8(rays, count, hits, found);
                        local.camera += static_cast<uint64_t>(count);
                        for (int i = 0; i < count; ++i) {
                            sampler.startSample(static_cast<uint32_t>(first + i), 1);
                            blocks[ti].put(film[i].x, film[i].y,
                                           integrator->Li(rays[i], found[i] ? &hits[i] : nullptr, sampler, local));
                        }
                    }
                }
            }
            const size_t finished = ++done;
            if (options.progress) {
                std::lock_guard<std::mutex> lock(progressMutex);
                options.progress(static_cast<double>(finished) / static_cast<double>(totalWork));
            }
        });
        Film film(width, height);
        for (const ImageBlock &block : blocks) film.merge(block);  // fixed order: thread-count independent
        Image mean{width, height, {}}, variance{width, height, {}};
        film.develop(mean.rgb, variance.rgb);
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
    for (const RayCounts &c : counts) {
        out.stats.cameraRays += c.camera;
        out.stats.shadowRays += c.shadow;
    }
    return out;
}

}  // namespace mcval
