// Shapes and their materials in a scene file: meshes, exact shapes, bsdfs and area emitters.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bsdf_loader.h"
#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// Throws at the node unless p is finite and within kMaxCoordinate; `what` names p in the message.
void requirePosition(const XmlContext &ctx, const pugi::xml_node &node, const std::string &what, const Vec3f &p);

/// Where loadShape appends what it reads: the scene's shapes, or a shapegroup's.
struct ShapeLists {
    std::vector<Mesh> &meshes;
    std::vector<Sphere> &spheres;
    std::vector<Disk> &disks;
    std::vector<Cylinder> &cylinders;
};

/// A <shape> (obj, ply, serialized, rectangle, cube, sphere, disk or cylinder) with its bsdf or ref (to a
/// bsdf anywhere in the file: defs.bsdfNodes) and area emitter, appended to its list in `out`.
void loadShape(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, ShapeLists out,
               Deferred &deferred);

/// Throws at the node unless the mesh's positions are finite and bounded and its normals unit length.
void requireFiniteMesh(const XmlContext &ctx, const pugi::xml_node &node, const Mesh &mesh);

}  // namespace mcval
