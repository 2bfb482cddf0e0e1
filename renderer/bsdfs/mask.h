// Mitsuba's `mask`: a nested BSDF with an opacity (a value, or a texture's luminance, clamped to [0, 1]; 0.5 by
// default): a leaf cut out of a rectangle. At a hit it is a MaskedBsdf of the opacity there.
#pragma once

#include <algorithm>
#include <memory>

#include "../textures/texture.h"
#include "textured_bsdf.h"

namespace mcval {

class MaskBsdf final : public Bsdf, public TexturedBsdf {
public:
    /// `opacity` null: the constant `constantOpacity`.
    MaskBsdf(std::shared_ptr<const Texture> opacity, float constantOpacity, std::shared_ptr<const Bsdf> nested)
        : m_opacity(std::move(opacity)), m_constant(constantOpacity), m_nested(std::move(nested)),
          m_nestedTextured(dynamic_cast<const TexturedBsdf *>(m_nested.get())) {}
    const Bsdf &at(const Vec2f &uv, BsdfScratch &scratch) const override {
        // The nested surface first: a textured one is made in the scratch's diffuse slot, the mask in its own.
        const Bsdf &nested = m_nestedTextured ? m_nestedTextured->at(uv, scratch) : *m_nested;
        scratch.masked = MaskedBsdf(opacityAt(uv), &nested);
        return scratch.masked;
    }
    bool readsUv() const override { return m_opacity || (m_nestedTextured && m_nestedTextured->readsUv()); }
    // Without a point (never used by the integrators that read it): the opacity at (0, 0).
    Color eval(const Vec3f &wi, const Vec3f &wo) const override { return m_nested->eval(wi, wo) * opacityAt({}); }
    float pdf(const Vec3f &wi, const Vec3f &wo) const override { return m_nested->pdf(wi, wo) * opacityAt({}); }
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override {
        return MaskedBsdf(opacityAt({}), m_nested.get()).sample(wi, u);
    }
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    /// Mitsuba's eval_1: an RGB texture's luminance, clamped to [0, 1].
    float opacityAt(const Vec2f &uv) const {
        if (!m_opacity) return m_constant;
        return std::clamp(luminance(m_opacity->eval(uv)), 0.f, 1.f);
    }
    std::shared_ptr<const Texture> m_opacity;
    float m_constant;
    std::shared_ptr<const Bsdf> m_nested;
    const TexturedBsdf *m_nestedTextured;
};

}  // namespace mcval
