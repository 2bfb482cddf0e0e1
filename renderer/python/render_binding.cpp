// Python binding of render(): numpy arrays out, the GIL released while rendering.
#include <chrono>
#include <map>
#include <string>

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>
#include <nanobind/stl/map.h>
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>

#include "../error.h"
#include "../integrators/registry.h"
#include "../render.h"
#include "../scene.h"

namespace nb = nanobind;
using namespace mcval;

namespace {

using Array = nb::ndarray<nb::numpy, float>;

/// How long a worker keeps spinning after a render from Python, which often renders again soon (the
/// bench renders step after step): see worker_warmth.h.
constexpr int kKeepWarmMilliseconds = 100;

/// Copies images into one new (count, H, W, 3) or (H, W, 3) array.
Array toNumpy(const std::vector<const Image *> &images, bool stacked) {
    const size_t h = images[0]->height, w = images[0]->width, n = images.size();
    float *data = new float[n * h * w * 3];
    for (size_t k = 0; k < n; ++k) std::copy(images[k]->rgb.begin(), images[k]->rgb.end(), data + k * h * w * 3);
    nb::capsule owner(data, [](void *p) noexcept { delete[] static_cast<float *>(p); });
    if (stacked) return Array(data, {n, h, w, 3}, owner);
    return Array(data, {h, w, 3}, owner);
}

nb::dict renderScene(const std::string &path, std::optional<int> spp, uint64_t seed, int threads, int batches,
                     const std::string &integrator, const std::map<std::string, std::string> &params,
                     const std::string &sampler) {
    RenderOutput out;
    double loadSeconds = 0.0;
    {
        nb::gil_scoped_release release;
        const auto start = std::chrono::steady_clock::now();
        const SceneDescription scene = loadScene(path, params, integrator);
        loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        RenderOptions options;
        options.spp = spp.value_or(0);
        options.seed = seed;
        options.threads = threads;
        options.batches = batches;
        options.integrator = integrator;
        options.sampler = sampler;
        options.keepWarmMilliseconds = kKeepWarmMilliseconds;
        out = render(scene, options);
    }
    nb::dict result;
    result["mean"] = toNumpy({&out.mean}, false);
    result["variance"] = toNumpy({&out.variance}, false);
    if (!out.batches.empty()) {
        std::vector<const Image *> ptrs;
        for (const Image &b : out.batches) ptrs.push_back(&b);
        result["batches"] = toNumpy(ptrs, true);
    } else {
        result["batches"] = toNumpy({&out.mean}, true);
    }
    const RenderStats &s = out.stats;
    nb::dict stats;
    stats["integrator"] = s.integrator;
    stats["sampler"] = s.sampler;
    stats["spp"] = s.spp;
    stats["batches"] = s.batches;
    stats["seed"] = s.seed;
    stats["load_seconds"] = loadSeconds;
    stats["bvh_seconds"] = s.bvhSeconds;
    stats["render_seconds"] = s.renderSeconds;
    stats["camera_rays"] = s.cameraRays;
    stats["shadow_rays"] = s.shadowRays;
    result["stats"] = stats;
    return result;
}

}  // namespace

void bindRender(nb::module_ &m) {
    nb::exception<SceneError>(m, "SceneError", PyExc_ValueError);
    // The docstring names the integrators this build registered; nanobind keeps the pointer, so it lives on.
    static const std::string doc =
        "Render a scene file with its integrator or `integrator`: " + integratorNameList() +
        ", and its sampler or `sampler` (independent or sobol)" +
        ". Returns {'mean': (H, W, 3), 'variance': (H, W, 3), 'batches': (K, H, W, 3), "
        "'stats': {...}} as float32 arrays; raises SceneError (a ValueError) for a bad scene.";
    m.def("render", &renderScene, nb::arg("scene"), nb::arg("spp") = nb::none(), nb::arg("seed") = 0,
          nb::arg("threads") = 0, nb::arg("batches") = 1, nb::arg("integrator") = "",
          nb::arg("params") = std::map<std::string, std::string>{}, nb::arg("sampler") = "", doc.c_str());
}
