// Rays per second of each integrator on a scene, beside a raw Embree loop that traces the
// same rays, in the same packets, with no shading: the physical limit of this machine for them.
//
//   build/bench_rays scenes/highpoly.xml [--spp N] [--repeats R] [--json PATH]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <tbb/parallel_for.h>

#include "camera.h"
#include "embree_scene.h"
#include "frame.h"
#include "integrators/integrator.h"
#include "render.h"
#include "scene.h"
#include "warp.h"

using namespace mcval;

namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

/// The rays an integrator traces, rebuilt with the renderer's own camera, sampler and spawn rule.
struct RaySet {
    std::vector<Ray> closest;   ///< camera rays (closest hit)
    std::vector<Ray> occlusion; ///< shadow or AO rays (any hit)
};

RaySet collectRays(const SceneDescription &scene, const EmbreeScene &embree, const std::string &integrator, int spp,
                   int aoSamples) {
    const Camera camera(scene.camera, scene.film.width, scene.film.height);
    RaySet rays;
    for (int y = 0; y < scene.film.height; ++y) {
        for (int x = 0; x < scene.film.width; ++x) {
            Sampler sampler(scene.sampler, 0, 0, static_cast<uint64_t>(y) * scene.film.width + x);
            for (int s = 0; s < spp; ++s) {
                sampler.startSample(static_cast<uint32_t>(s));
                const Vec2f j = sampler.next2D();
                const Ray ray = camera.generateRay(float(x) + j.x, float(y) + j.y);
                rays.closest.push_back(ray);
                sampler.startSample(static_cast<uint32_t>(s), 1);
                Hit hit;
                if (integrator == "normals" || !embree.intersect(ray, hit) || dot(hit.ns, ray.d) >= 0.f) continue;
                if (integrator == "simple") {
                    for (const PointLight &light : scene.pointLights) {
                        const Vec3f to = light.position - hit.p;
                        const float dist = norm(to);
                        if (dot(hit.ns, to) > 0.f) rays.occlusion.push_back(spawnRay(hit, to / dist, dist * (1.f - 1e-4f)));
                    }
                } else {
                    const Frame frame(hit.ns);
                    for (int i = 0; i < aoSamples; ++i)
                        rays.occlusion.push_back(spawnRay(hit, frame.toWorld(squareToCosineHemisphere(sampler.next2D())), 1e30f));
                }
            }
        }
    }
    return rays;
}

/// Seconds to trace every ray of the set in parallel, doing nothing with the answers, in the
/// renderer's best mode: camera rays in packets of kPacketSize (the samples of one pixel), the
/// occlusion rays in packets of kPacketSize as they were made (coherent for simple's shadow rays,
/// which share a light; incoherent for ao's).
double traceRaw(const EmbreeScene &embree, const RaySet &rays, int spp, bool coherent) {
    const auto start = std::chrono::steady_clock::now();
    const size_t pixels = rays.closest.size() / static_cast<size_t>(spp);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pixels, 64), [&](const auto &r) {
        Hit hits[kPacketSize];
        bool found[kPacketSize];
        for (size_t p = r.begin(); p != r.end(); ++p)
            for (int first = 0; first < spp; first += kPacketSize)
                embree.intersect16(&rays.closest[p * spp + first], std::min(kPacketSize, spp - first), hits, found);
    });
    const size_t packets = (rays.occlusion.size() + kPacketSize - 1) / kPacketSize;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, packets, 64), [&](const auto &r) {
        OcclusionPacket packet;
        for (size_t p = r.begin(); p != r.end(); ++p) {
            packet.clear();
            const size_t first = p * kPacketSize;
            for (size_t i = first; i < std::min(first + kPacketSize, rays.occlusion.size()); ++i) {
                const Ray &ray = rays.occlusion[i];
                packet.set(static_cast<int>(i - first), ray.o, ray.d, ray.tfar);
            }
            embree.occluded(packet, coherent);
        }
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"Rays per second of each integrator beside a raw Embree loop over the same rays."};
    std::string scenePath, jsonPath;
    int spp = 16, repeats = 5, aoSamples = 1;
    app.add_option("scene", scenePath, "scene file")->required()->check(CLI::ExistingFile);
    app.add_option("--spp", spp, "samples per pixel (default 16)")->check(CLI::PositiveNumber);
    app.add_option("--ao-samples", aoSamples, "occlusion rays per camera hit for ao (default 1, as the ao integrator's)")
        ->check(CLI::PositiveNumber);
    app.add_option("--repeats", repeats, "runs per measurement; the median is reported (default 5)")
        ->check(CLI::PositiveNumber);
    app.add_option("--json", jsonPath, "also write the figures as JSON");
    CLI11_PARSE(app, argc, argv);

    const SceneDescription scene = loadScene(scenePath);
    const EmbreeScene embree(scene.meshes, scene.spheres, scene.disks, scene.cylinders, scene.bsdfs);
    std::printf("%s: %dx%d, %d spp, %zu triangles; medians of %d runs\n", scenePath.c_str(), scene.film.width,
                scene.film.height, spp, [&] { size_t n = 0; for (const Mesh &m : scene.meshes) n += m.indices.size() / 3; return n; }(),
                repeats);
    std::printf("%-10s %14s %14s %8s\n", "integrator", "renderer Mrays/s", "raw Mrays/s", "ratio");
    std::string json = "{\n  \"scene\": \"" + scenePath + "\",\n  \"spp\": " + std::to_string(spp) + ",\n  \"integrators\": {";
    bool first = true;
    for (const char *name : {"normals", "simple", "ao"}) {
        RenderOptions options;
        options.spp = spp;
        options.integrator = name;
        std::vector<double> rendered, raw;
        uint64_t rayCount = 0;
        for (int r = 0; r < repeats; ++r) {
            const RenderOutput out = render(scene, options);
            rayCount = out.stats.cameraRays + out.stats.shadowRays;
            rendered.push_back(double(rayCount) / out.stats.renderSeconds);
        }
        const RaySet rays = collectRays(scene, embree, name, spp, aoSamples);
        const double rawCount = double(rays.closest.size() + rays.occlusion.size());
        for (int r = 0; r < repeats; ++r) raw.push_back(rawCount / traceRaw(embree, rays, spp, std::string(name) == "simple"));
        const double o = median(rendered), w = median(raw);
        std::printf("%-10s %14.2f %14.2f %8.2f   (%llu rays; raw set %.0f)\n", name, o / 1e6, w / 1e6, o / w,
                    static_cast<unsigned long long>(rayCount), rawCount);
        json += std::string(first ? "" : ",") + "\n    \"" + name + "\": {\"renderer_rays_per_second\": " + std::to_string(o) +
                ", \"raw_rays_per_second\": " + std::to_string(w) + ", \"ratio\": " + std::to_string(o / w) + "}";
        first = false;
    }
    json += "\n  }\n}\n";
    if (!jsonPath.empty()) std::ofstream(jsonPath) << json;
    return 0;
}
