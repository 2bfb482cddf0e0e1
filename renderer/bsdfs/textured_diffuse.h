// Mitsuba's `diffuse` with a textured reflectance: at each surface point a Lambertian reflector of the texture's
// value there. The integrators that read any BSDF ask for that point's DiffuseBsdf (EmbreeScene::bsdfAt).
#pragma once

#include <memory>

#include "../textures/texture.h"
#include "diffuse.h"

namespace mcval {

class TexturedDiffuseBsdf final : public Bsdf {
public:
    explicit TexturedDiffuseBsdf(std::shared_ptr<const Texture> reflectance) : m_reflectance(std::move(reflectance)) {}
    /// The surface at texture coordinates uv.
    DiffuseBsdf at(const Vec2f &uv) const { return DiffuseBsdf(m_reflectance->eval(uv)); }
    // Without a point, the surface of (u, v) = (0, 0): what a caller that forgot bsdfAt would see, never used
    // by the integrators that read textures.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override { return at({}).eval(wi, wo); }
    float pdf(const Vec3f &wi, const Vec3f &wo) const override { return at({}).pdf(wi, wo); }
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override { return at({}).sample(wi, u); }
    /// None: its albedo varies over the surface (the packet paths, which read one albedo per shape, refuse it).
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    std::shared_ptr<const Texture> m_reflectance;
};

}  // namespace mcval
