// Mitsuba's directional emitter (src/emitters/directional.cpp): one direction, weight E, pdf 1.
#include <limits>

#include "delta_lights.h"

namespace mcval {

DirectionalEmitter::DirectionalEmitter(const DirectionalLight &light)
    : m_irradiance(light.irradiance), m_direction(normalize(light.direction)) {}

EmitterSample DirectionalEmitter::sample(const Vec3f &, const Vec2f &) const {
    EmitterSample s;
    s.d = -m_direction;
    // Infinitely far: a shadow ray toward it runs to the end of the scene (Mitsuba: twice its bounding sphere).
    s.dist = std::numeric_limits<float>::infinity();
    s.pdf = 1.f;
    s.delta = true;
    s.weight = m_irradiance;
    return s;
}

}  // namespace mcval
