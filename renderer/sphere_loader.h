// Mitsuba's <shape type="sphere">: its properties read and checked, the result in world space.
#pragma once

#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// The sphere of `center` (default 0, 0, 0) and `radius` (default 1) under `to_world`, with
/// `flip_normals`. As in Mitsuba, to_world may translate, rotate and scale uniformly, and a mirroring
/// one flips the normals; a shear or a non-uniform scale is an error (an ellipsoid needs a mesh), as
/// is a radius that is not positive or a sphere outside scene_limits.h.
Sphere loadSphere(XmlProps &props, const Transform &toWorld);

}  // namespace mcval
