// What the render tests count in an image: values that are not finite, and values that are not 0.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

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
