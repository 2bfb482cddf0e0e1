// Mitsuba's exact disk: the ray meets the plane z = 0 of object space (in double), inside the unit
// circle; the hit point is put back on that plane, the normal is to_world's inverse transpose of +z.
#pragma once

#include "scene.h"

namespace mcval {

/// The t in [tnear, tfar] where o + t d meets the disk, in double; false if none. Both sides are hit.
bool intersectShape(const Disk &disk, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t);

/// The point at t on the ray, moved onto the disk's plane, and its unit normal (object-space +z under
/// to_world, -z with flip_normals).
void shapeHitPoint(const Disk &disk, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n);

/// The world-space box around the disk (its ellipse's exact extent along each axis).
void shapeBounds(const Disk &disk, Vec3d &lo, Vec3d &hi);

/// About the disk's smaller semi-axis in world space (within a factor sqrt 2): its size, for the
/// spawn offset floor.
double shapeSize(const Disk &disk);

}  // namespace mcval
