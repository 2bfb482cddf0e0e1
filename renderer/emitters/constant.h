// Mitsuba's `constant` emitter: an environment of one radiance, infinitely far away.
#pragma once

#include "emitter.h"

namespace mcval {

class ConstantEmitter final : public Emitter {
public:
    explicit ConstantEmitter(const Color &radiance) : m_radiance(radiance) {}
    EmitterKind kind() const override { return EmitterKind::Constant; }
    bool isDelta() const override { return false; }
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override;
    /// L along every ray that escapes the scene.
    Color eval(const EmitterHit &) const override { return m_radiance; }
    float pdf(const Vec3f &ref, const EmitterHit &at) const override;

private:
    Color m_radiance;
};

}  // namespace mcval
