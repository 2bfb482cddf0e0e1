// Mitsuba's exact cylinder: open (no caps), hit from both sides, its normal pointing outward from
// either side; intersected in double in object space (the unit cylinder), the hit point put back on
// the surface.
#pragma once

#include "scene.h"

namespace mcval {

/// The nearest t in [tnear, tfar] where o + t d meets the cylinder, in double; false if none.
bool intersectShape(const Cylinder &cyl, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t);

/// The point at t on the ray, moved radially onto the cylinder, and its unit normal: outward (to_world's
/// inverse transpose of the object-space radial direction), inward with flip_normals.
void shapeHitPoint(const Cylinder &cyl, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n);

/// The world-space box around the cylinder (around its two end ellipses).
void shapeBounds(const Cylinder &cyl, Vec3d &lo, Vec3d &hi);

/// The smaller of the cylinder's radius and length in world space: its size, for the spawn offset floor.
double shapeSize(const Cylinder &cyl);

}  // namespace mcval
