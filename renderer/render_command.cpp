#include "render_command.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "error.h"
#include "exr_output.h"
#include "raw_output.h"
#include "progress.h"
#include "integrators/registry.h"
#include "render.h"
#include "scene.h"
#include "scene_limits.h"

namespace mcval {

namespace {

/// A message fit for one terminal line: control characters (from file names or values in the
/// scene) escaped, and very long messages shortened in the middle.
std::string oneLine(const std::string &message) {
    constexpr size_t kMaxLength = 1000;
    std::string out;
    for (const unsigned char c : message) {
        if (c >= 0x20 && c != 0x7f) {
            out += static_cast<char>(c);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02x", c);
            out += buf;
        }
    }
    if (out.size() > kMaxLength) out = out.substr(0, kMaxLength / 2) + " ... " + out.substr(out.size() - kMaxLength / 2);
    return out;
}

/// One line per registered integrator: its name and what it computes.
std::string integratorHelp() {
    std::string help;
    for (const std::string &name : integratorNames())
        help += "  " + name + std::string(name.size() < 10 ? 10 - name.size() : 1, ' ') + findIntegrator(name)->description + "\n";
    return help;
}

}  // namespace

int runRenderCommand(const std::vector<std::string> &args, int keepWarmMilliseconds) {
    CLI::App app{"Render a scene file (a subset of Mitsuba 3 XML) with one of the integrators below.\n"
                 "Writes OpenEXR: R,G,B (mean), variance.R/G/B, and batch<k>.R/G/B with --batches K.\n"
                 "Integrators:\n" + integratorHelp(), "render"};
    std::string scenePath, outPath, integrator, sampler;
    int spp = 0, threads = 0, batches = 1;
    uint64_t seed = 0;
    std::vector<std::string> defines;
    bool quiet = false, raw = false;
    app.add_option("scene", scenePath, "scene file (.xml)")->required()->check(CLI::ExistingFile);
    app.add_option("-o,--output", outPath, "output .exr (default: the scene's name, .exr, in the current folder)");
    app.add_option("--spp", spp, "samples per pixel (per batch; default: the scene's sample_count)")
        ->check(CLI::Range(1, kMaxSampleCount));
    app.add_option("--seed", seed, "random seed (default 0)");
    app.add_option("--threads", threads, "worker threads (default: all cores)")->check(CLI::NonNegativeNumber);
    app.add_option("--batches", batches, "independent images to render, each with --spp samples (default 1)")
        ->check(CLI::Range(1, kMaxBatches));
    app.add_option("--integrator", integrator, integratorNameList() + " (default: the scene's)")
        ->check(CLI::IsMember(integratorNames()));
    app.add_option("--sampler", sampler, "independent (independent uniform values) or sobol (Owen-scrambled Sobol "
                                         "points) (default: the scene's <sampler>)")
        ->check(CLI::IsMember({"independent", "sobol"}));
    app.add_option("-D,--define", defines, "set a scene parameter: -D name=value (overrides its <default>)");
    app.add_flag("-q,--quiet", quiet, "no progress bar or summary");
    app.footer("render --serve (alone) reads renders' arguments on stdin, one after another, and answers each with\n"
               "its exit status on stdout: the harness's long-lived worker (see renderer/serve.h).");
    app.add_flag("--raw", raw, "write raw float32 images after one header line instead of OpenEXR: the batches (or the "
                               "mean for one batch), for a reader on this machine that reads the file at once "
                               "(see renderer/raw_output.h)");
    try {
        std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
        app.parse(reversed);
    } catch (const CLI::ParseError &e) {
        return app.exit(e);
    }

    try {
        std::map<std::string, std::string> params;
        for (const std::string &d : defines) {
            const size_t eq = d.find('=');
            if (eq == std::string::npos || eq == 0) throw SceneError("-D expects name=value, got \"" + d + "\"");
            params[d.substr(0, eq)] = d.substr(eq + 1);
        }
        if (outPath.empty()) outPath = std::filesystem::path(scenePath).stem().string() + ".exr";
        requireWritableOutput(outPath);  // before the work, not after it
        const auto start = std::chrono::steady_clock::now();
        const SceneDescription scene = loadScene(scenePath, params, integrator);
        OutputInfo info{scenePath, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                        scene.film.componentFormat == "float16"};

        RenderOptions options;
        options.spp = spp;
        options.seed = seed;
        options.threads = threads;
        options.batches = batches;
        options.integrator = integrator;
        options.sampler = sampler;
        // A render limited to some cores shares the machine (a cluster's worker): it leaves the rest idle.
        options.keepWarmMilliseconds = threads > 0 ? 0 : keepWarmMilliseconds;
        ProgressBar bar;
        if (!quiet) options.progress = [&bar](double f) { bar.update(f); };
        const RenderOutput output = render(scene, options);
        bar.finish();
        if (raw)
            writeRaw(outPath, output, info);
        else
            writeExr(outPath, output, info);
        if (!quiet) {
            const RenderStats &s = output.stats;
            const double rays = double(s.cameraRays + s.shadowRays);
            std::fprintf(stderr, "%s: %s, %s sampler, %dx%d, %d spp x %d batches; load %.3fs, BVH %.3fs, render %.3fs, "
                                 "%.1f Mrays/s\n",
                         outPath.c_str(), s.integrator.c_str(), s.sampler.c_str(), output.mean.width, output.mean.height, s.spp,
                         s.batches, info.loadSeconds, s.bvhSeconds, s.renderSeconds, rays / s.renderSeconds / 1e6);
        }
        return 0;
    } catch (const SceneError &e) {
        std::fprintf(stderr, "error: %s\n", oneLine(e.what()).c_str());
        return 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "error: %s\n", oneLine(e.what()).c_str());
        return 2;
    }
}

}  // namespace mcval
