// What a loaded shape's BSDF reflects, for tests that check what a scene file gave it.
#pragma once

#include <optional>

#include "scene.h"

namespace mcval::test {

/// The Lambertian albedo of the front of shape's BSDF.
template <typename Shape>
Color frontAlbedo(const SceneDescription &scene, const Shape &shape) {
    return *scene.bsdfs.at(shape.bsdf)->lambertianAlbedo(true);
}

/// The albedo of the back of a two-sided shape's BSDF; none for a one-sided one (black from behind).
template <typename Shape>
std::optional<Color> backAlbedo(const SceneDescription &scene, const Shape &shape) {
    const Bsdf &bsdf = *scene.bsdfs.at(shape.bsdf);
    return bsdf.twoSided() ? bsdf.lambertianAlbedo(false) : std::nullopt;
}

}  // namespace mcval::test
