// Mitsuba's <shape type="shapegroup"> and <shape type="instance">, flattened as the file is read: a group's
// shapes are kept aside, and each instance appends copies of them under its to_world.
#pragma once

#include "scene.h"
#include "shape_loader.h"
#include "xml_props.h"

namespace mcval {

/// A top-level <shape type="shapegroup" id="...">: its member shapes, stored in defs.groups under its id
/// (without an id, checked and dropped: nothing can place it). Refused as Mitsuba refuses them: a
/// shapegroup or instance inside it, an emitter (Mitsuba does not instance emitters), anything but a
/// <shape>.
void loadShapeGroup(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred);

/// A <shape type="instance"> with one <ref id> to a shapegroup anywhere in the file (call it once every
/// shapegroup is read, as Mitsuba resolves references): the group's shapes under the instance's to_world
/// (applied after each member's own), appended to the scene. A sphere under a to_world that scales
/// unevenly or shears is refused: it would be an ellipsoid.
void loadInstance(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, SceneDescription &scene);

}  // namespace mcval
