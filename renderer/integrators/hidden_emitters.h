// hide_emitters for the integrators that see emitters: the camera ray passes through every emitting surface
// to what lies behind it, as Mitsuba's direct and path do (either side of the surface, and without counting
// as a vertex of the path).
#pragma once

#include "integrator.h"

namespace mcval {

/// The most emitting surfaces a hidden-emitter camera ray passes through.
constexpr int kMaxSkippedEmitters = 64;

/// Moves `hit` (if `found`) past the area emitters along unit d; returns whether a surface that emits nothing
/// lies behind them. Past kMaxSkippedEmitters surfaces the ray is taken to find nothing.
inline bool skipAreaEmitters(const EmbreeScene &embree, const Vec3f &d, Hit &hit, bool found, RayCounts &counts) {
    for (int k = 0; found && hit.emitter >= 0 && k < kMaxSkippedEmitters; ++k) {
        found = embree.intersect(spawnRay(hit, d, 1e30f), hit);
        counts.shadow += 1;
    }
    return found && hit.emitter < 0;
}

}  // namespace mcval
