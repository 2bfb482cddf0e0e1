// BSDFs whose parameters vary over the surface (a textured diffuse reflectance, a mask's opacity): the
// integrators that read any BSDF ask for the one at a hit's (u, v) (EmbreeScene::bsdfAt), made in a scratch
// that lives as long as they use it.
#pragma once

#include "diffuse.h"
#include "masked.h"

namespace mcval {

/// Room for the surfaces a textured BSDF makes at one point.
struct BsdfScratch {
    DiffuseBsdf diffuse{Color(0.f, 0.f, 0.f)};
    MaskedBsdf masked;
};

class TexturedBsdf {
public:
    virtual ~TexturedBsdf() = default;
    /// The BSDF at texture coordinates uv, in `scratch` or one it holds.
    virtual const Bsdf &at(const Vec2f &uv, BsdfScratch &scratch) const = 0;
    /// Whether it reads (u, v): a shape without texture coordinates cannot have it.
    virtual bool readsUv() const = 0;
};

}  // namespace mcval
