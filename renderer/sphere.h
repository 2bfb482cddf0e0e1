// The exact sphere: ray intersection in double with a cancellation-free quadratic, hit points
// re-projected onto the surface, and its Embree 3 user geometry.
#pragma once

#include <embree3/rtcore.h>

#include "scene.h"

namespace mcval {

/// The nearest t in [tnear, tfar] where o + t d meets the sphere, computed in double; false if none.
bool intersectSphere(const Sphere &sphere, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t);

/// intersectSphere under the name the user-geometry callbacks call (user_geometry.h).
inline bool intersectShape(const Sphere &sphere, const Vec3f &o, const Vec3f &d, float tnear, float tfar, double &t) {
    return intersectSphere(sphere, o, d, tnear, tfar, t);
}

/// The box around the sphere, in double (center -/+ radius).
void shapeBounds(const Sphere &sphere, Vec3d &lo, Vec3d &hi);

/// The point at t on the ray, moved onto the sphere (c + r (p - c) / |p - c|), and its unit
/// geometric normal (outward unless the sphere's normals are flipped).
void sphereHitPoint(const Sphere &sphere, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n);

/// Attaches the sphere to the scene as one Embree user geometry; it must outlive the scene.
void attachSphere(RTCDevice device, RTCScene scene, const Sphere &sphere);

}  // namespace mcval
