// Mitsuba's `area` emitter: radiance L leaving the front side of a shape (the side its shading normal
// points to), sampled by the shape's ShapeSampler.
#pragma once

#include <memory>

#include "shape_sampler.h"

namespace mcval {

class AreaEmitter final : public Emitter {
public:
    AreaEmitter(const Color &radiance, std::unique_ptr<ShapeSampler> shape)
        : m_radiance(radiance), m_shape(std::move(shape)) {}
    EmitterKind kind() const override { return EmitterKind::Area; }
    bool isDelta() const override { return false; }
    /// A point of the shape; weight L / pdf where ref sees its front, else weight and pdf 0.
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override;
    /// L on the front side, 0 behind (Mitsuba's cos_theta(si.wi) > 0).
    Color eval(const EmitterHit &at) const override;
    /// The shape's density by solid angle where the ray meets the front (dot(d, ns) < 0), else 0.
    float pdf(const Vec3f &ref, const EmitterHit &at) const override;

private:
    /// Whether a ray along d meets the side of the surface that emits: the side its shading normal ns faces.
    static bool frontFacing(const Vec3f &d, const Vec3f &ns) { return dot(d, ns) < 0.f; }
    Color m_radiance;
    std::unique_ptr<ShapeSampler> m_shape;
};

}  // namespace mcval
