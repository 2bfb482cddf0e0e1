// Mitsuba's `mask` at one surface point: its nested BSDF where the surface is there (opacity alpha), a hole
// the light passes straight through elsewhere (a null lobe, drawn with probability 1 - alpha).
#pragma once

#include <limits>

#include "bsdf.h"

namespace mcval {

class MaskedBsdf final : public Bsdf {
public:
    MaskedBsdf() = default;
    MaskedBsdf(float opacity, const Bsdf *nested) : m_opacity(opacity), m_nested(nested) {}
    /// alpha f(wi, wo): the null lobe has no density off its one direction.
    Color eval(const Vec3f &wi, const Vec3f &wo) const override { return m_nested->eval(wi, wo) * m_opacity; }
    float pdf(const Vec3f &wi, const Vec3f &wo) const override { return m_nested->pdf(wi, wo) * m_opacity; }
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override { return sample(wi, u, 0.5f); }
    /// The nested BSDF's sample where uLobe < alpha (uLobe rescaled for it), its density times alpha and so its
    /// weight unchanged; otherwise straight on, weight 1, a delta lobe. (Mitsuba's mask leaves the nested
    /// sample's pdf without alpha while its pdf() has it: the two disagree where 0 < alpha < 1.)
    BsdfSample sample(const Vec3f &wi, const Vec2f &u, float uLobe) const override {
        if (uLobe < m_opacity) {
            BsdfSample s = m_nested->sample(wi, u, uLobe / m_opacity);
            s.pdf *= m_opacity;
            return s;
        }
        BsdfSample s;
        s.wo = -wi;
        s.weight = {1.f, 1.f, 1.f};
        s.pdf = std::numeric_limits<float>::infinity();
        return s;
    }
    std::optional<Color> lambertianAlbedo(bool) const override { return std::nullopt; }

private:
    float m_opacity = 1.f;
    const Bsdf *m_nested = nullptr;
};

}  // namespace mcval
