// Mitsuba's <shape type="disk"> and <shape type="cylinder">: their properties read and checked, the
// result an object-to-world map in double.
#pragma once

#include <optional>
#include <string>

#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// The unit disk at z = 0 under `to_world` (any invertible affine map, as Mitsuba's), with
/// `flip_normals`. A degenerate to_world, or a disk outside scene_limits.h, is an error.
Disk loadDisk(XmlProps &props, const Transform &toWorld);

/// The cylinder from `p0` (default 0, 0, 0) to `p1` (default 0, 0, 1) of `radius` (default 1) under
/// `to_world`, composed as Mitsuba does (to_world * translate(p0) * frame(p1 - p0) * scale(r, r, |p1 - p0|)),
/// with `flip_normals`. A radius that is not positive, p0 = p1, a degenerate to_world, or a cylinder
/// outside scene_limits.h, is an error.
Cylinder loadCylinder(XmlProps &props, const Transform &toWorld);

/// Why float32 and Embree cannot trace the disk or cylinder as it is placed (a degenerate map, a box beyond
/// kMaxCoordinate, a size too small for its distance from the origin), or nothing if they can.
std::optional<std::string> whyUntraceable(const Disk &disk);
std::optional<std::string> whyUntraceable(const Cylinder &cyl);

}  // namespace mcval
