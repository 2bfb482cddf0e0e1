// Mitsuba's `diffuse` with a textured reflectance: at each surface point a Lambertian reflector of the texture's
// value there. The integrators that read any BSDF ask for that point's DiffuseBsdf (EmbreeScene::bsdfAt).
#pragma once

#include <memory>

#include "../textures/texture.h"
#include "textured_bsdf.h"

namespace mcval {

class TexturedDiffuseBsdf final : public Bsdf, public TexturedBsdf {
public:
    explicit TexturedDiffuseBsdf(std::shared_ptr<const Texture> reflectance) : m_reflectance(std::move(reflectance)) {}
    const Bsdf &at(const Vec2f &uv, BsdfScratch &scratch) const override {
        scratch.diffuse = DiffuseBsdf(m_reflectance->eval(uv));
        return scratch.diffuse;
    }
    bool readsUv() const override { return true; }
    // Without a point, the surface of (u, v) = (0, 0): what a caller that forgot bsdfAt would see, never used
    // by the integrators that read textures.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override { return surface().eval(wi, wo); }
    float pdf(const Vec3f &wi, const Vec3f &wo) const override { return surface().pdf(wi, wo); }
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override { return surface().sample(wi, u); }
    /// None: its albedo varies over the surface (the packet paths, which read one albedo per shape, refuse it).
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    DiffuseBsdf surface() const { return DiffuseBsdf(m_reflectance->eval({})); }
    std::shared_ptr<const Texture> m_reflectance;
};

}  // namespace mcval
