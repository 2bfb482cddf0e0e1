// What the integrators that combine emitter and BSDF sampling share: the power heuristic, the test for a light
// sample not worth its shadow ray and the change to a shading frame's local coordinates.
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

/// Whether a light sample of weight `weight` carries nothing through a BSDF value `f` whatever its shadow ray
/// finds (the light below a diffuse surface: half of a constant emitter's samples), so that the ray need not be
/// traced. A weight that is not finite is traced: 0 times it is NaN, which the image must show.
inline bool passesNothing(const Vec3f &f, const Vec3f &weight) {
    return f.x == 0.f && f.y == 0.f && f.z == 0.f && std::isfinite(weight.x) && std::isfinite(weight.y) &&
           std::isfinite(weight.z);
}

/// v in the frame's local coordinates (z: its normal).
inline Vec3f toLocal(const Frame &frame, const Vec3f &v) { return {dot(v, frame.s), dot(v, frame.t), dot(v, frame.n)}; }

}  // namespace mcval
