#include <cmath>

#include "scene.h"

namespace mcval {

float FilterSpec::eval(float x) const {
    if (type == Type::Box) return std::abs(x) <= 0.5f ? 1.f : 0.f;
    // Mitsuba's windowed gaussian: shifted so that it reaches 0 at the radius.
    const float alpha = -1.f / (2.f * stddev * stddev);
    const float r = radius();
    return std::max(0.f, std::exp(alpha * x * x) - std::exp(alpha * r * r));
}

}  // namespace mcval
