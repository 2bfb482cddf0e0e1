// Points drawn on a shape that emits, and the density by solid angle that this gives a direction from a
// reference point (Mitsuba's Shape::sample_direction / pdf_direction). Meshes (rectangle, cube, obj, ply,
// serialized), disks and cylinders are sampled uniformly by area; a sphere seen from outside by the cone of
// directions it covers, from inside by area, as Mitsuba's sphere does.
#pragma once

#include <memory>
#include <vector>

#include "emitter.h"

namespace mcval {

/// A point drawn on a shape, seen from a reference point.
struct ShapeSample {
    Vec3f p;
    Vec3f ng;        ///< unit geometric normal on the front (Hit::ng at p)
    Vec3f ns;        ///< unit shading normal (Hit::ns at p)
    Vec3f d;         ///< unit direction from the reference point to p
    float dist = 0.f;
    float pdf = 0.f; ///< density of d by solid angle (0 where the conversion from area is not finite)
};

class ShapeSampler {
public:
    virtual ~ShapeSampler() = default;
    /// A point on the shape drawn with u in [0, 1)^2, and its direction's density from ref.
    virtual ShapeSample sample(const Vec3f &ref, const Vec2f &u) const = 0;
    /// The density by solid angle of the direction toward `at` (a point of the shape) from ref.
    virtual float pdf(const Vec3f &ref, const EmitterHit &at) const = 0;
};

/// A sampler over the shape's surface, uniform by area for meshes, disks and cylinders (the cylinder by
/// its exact area element under any to_world), by the visible cone for a sphere seen from outside.
std::unique_ptr<ShapeSampler> makeShapeSampler(const Mesh &mesh);
std::unique_ptr<ShapeSampler> makeShapeSampler(const Sphere &sphere);
std::unique_ptr<ShapeSampler> makeShapeSampler(const Disk &disk);
std::unique_ptr<ShapeSampler> makeShapeSampler(const Cylinder &cylinder);

/// From a density by area to one by solid angle at ref (Mitsuba's dist^2 / |cos|): 0 where not finite.
inline float areaToSolidAngle(float pdfArea, float dist, const Vec3f &d, const Vec3f &n) {
    const float x = dist * dist / std::abs(dot(d, n));
    return std::isfinite(x) ? pdfArea * x : 0.f;
}

}  // namespace mcval
