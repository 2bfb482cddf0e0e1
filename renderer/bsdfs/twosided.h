// Mitsuba's `twosided`: one BSDF on the front, another (or the same) on the back, each side seen as its
// BSDF's front.
#pragma once

#include <memory>

#include "bsdf.h"

namespace mcval {

class TwoSidedBsdf final : public Bsdf {
public:
    TwoSidedBsdf(std::shared_ptr<const Bsdf> front, std::shared_ptr<const Bsdf> back)
        : m_front(std::move(front)), m_back(std::move(back)) {}
    Color eval(const Vec3f &wi, const Vec3f &wo) const override;
    float pdf(const Vec3f &wi, const Vec3f &wo) const override;
    BsdfSample sample(const Vec3f &wi, const Vec2f &u) const override;
    BsdfSample sample(const Vec3f &wi, const Vec2f &u, float uLobe) const override;
    /// Each side: its own BSDF's front.
    std::optional<Color> lambertianAlbedo(bool front) const override {
        return (front ? m_front : m_back)->lambertianAlbedo(true);
    }
    bool twoSided() const override { return true; }

private:
    std::shared_ptr<const Bsdf> m_front, m_back;
};

}  // namespace mcval
