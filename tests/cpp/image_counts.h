// What the render tests count in an image: values that are not finite, and values that are not 0.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "render.h"
#include "scene.h"

struct ImageCounts {
    size_t nonFinite = 0;
    size_t nonZero = 0;
};

inline ImageCounts countValues(const std::vector<float> &values) {
    ImageCounts c;
    for (float v : values) {
        c.nonFinite += !std::isfinite(v);
        c.nonZero += v != 0.f;
    }
    return c;
}

/// `scene` under normals, simple and ao at 2 spp: no value that is not finite, and a tenth or more lit.
inline void expectFiniteAndLitUnderEveryIntegrator(const mcval::SceneDescription &scene) {
    for (const char *integrator : {"normals", "simple", "ao"}) {
        mcval::RenderOptions options;
        options.spp = 2;
        options.integrator = integrator;
        const mcval::RenderOutput out = mcval::render(scene, options);
        const ImageCounts counts = countValues(out.mean.rgb);
        EXPECT_EQ(counts.nonFinite, 0u) << integrator;
        EXPECT_GT(counts.nonZero, out.mean.rgb.size() / 10) << integrator;
    }
}
