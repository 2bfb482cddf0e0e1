// Mitsuba's <shape type="sphere">: its properties read and checked, the result in world space.
#pragma once

#include <optional>
#include <string>

#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// The sphere of `center` (default 0, 0, 0) and `radius` (default 1) under `to_world`, with
/// `flip_normals`. As in Mitsuba, to_world may translate, rotate and scale uniformly, and a mirroring
/// one flips the normals; a shear or a non-uniform scale is an error (an ellipsoid needs a mesh), as
/// is a radius that is not positive or a sphere outside scene_limits.h.
Sphere loadSphere(XmlProps &props, const Transform &toWorld);

/// Why a sphere cannot be placed, and the property at fault (to_world or radius).
struct SphereRefusal {
    std::string property, reason;
};

/// `sphere` under a further transform, into `out`; or, if that is not a similarity or the result breaks
/// scene_limits.h, why not (and `out` is unchanged). `ownTransform`: the sphere's own to_world, which
/// flips its normals if it mirrors (as Mitsuba's does); an instance's to_world transforms the normals
/// with the surface, so a mirrored sphere stays front side out (as in Mitsuba).
std::optional<SphereRefusal> placeSphere(const Sphere &sphere, const Transform &toWorld, bool ownTransform,
                                         Sphere &out);

}  // namespace mcval
