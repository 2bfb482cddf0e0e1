// What the integrators that combine emitter and BSDF sampling share: the power heuristic and the change
// to a shading frame's local coordinates.
#pragma once

#include <cmath>

#include "../frame.h"

namespace mcval {

/// Mitsuba's mis_weight: the power heuristic, 0 where it is not finite.
inline float misWeight(float pdfA, float pdfB) {
    pdfA *= pdfA;
    pdfB *= pdfB;
    const float w = pdfA / (pdfA + pdfB);
    return std::isfinite(w) ? w : 0.f;
}

/// v in the frame's local coordinates (z: its normal).
inline Vec3f toLocal(const Frame &frame, const Vec3f &v) { return {dot(v, frame.s), dot(v, frame.t), dot(v, frame.n)}; }

}  // namespace mcval
