// Shapes and their materials in a scene file: meshes, exact shapes, bsdfs and area emitters.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// Elements the chosen integrator may not use, judged once the integrator is known.
struct Deferred {
    std::vector<std::pair<pugi::xml_node, std::string>> nonDiffuseBsdfs, areaEmitters;
    /// A diffuse BSDF whose reflectance we cannot read (`given`: a texture, a per-wavelength spectrum):
    /// refused where the integrator reads the reflectance, skipped elsewhere (`what` in the note).
    struct UnreadReflectance {
        pugi::xml_node node;
        std::string what, given;
    };
    std::vector<UnreadReflectance> unreadReflectances;
    /// Top-level <texture>s: read only through a BSDF, which then is an unread reflectance.
    std::vector<std::pair<pugi::xml_node, std::string>> textures;
    /// Emitters of types no integrator of ours uses (directional, spot, projector, envmap): skipped.
    std::vector<std::pair<pugi::xml_node, std::string>> otherEmitters;
};

/// A <shape type="shapegroup">'s members, in the group's space: kept aside, rendered only through instances.
struct ShapeGroup {
    std::vector<Mesh> meshes;
    std::vector<Sphere> spheres;
    std::vector<Disk> disks;
    std::vector<Cylinder> cylinders;
};

/// What earlier elements defined, for a <ref id>: bsdfs (their reflectance) and shapegroups, which only
/// an instance may refer to.
struct Definitions {
    std::map<std::string, Color> bsdfs;
    std::map<std::string, ShapeGroup> groups;
    uint64_t instancedTriangles = 0, instancedShapes = 0;  ///< copies made by instances so far (bounded)
};

/// Throws at the node unless p is finite and within kMaxCoordinate; `what` names p in the message.
void requirePosition(const XmlContext &ctx, const pugi::xml_node &node, const std::string &what, const Vec3f &p);

/// A <bsdf>'s reflectance; a type other than diffuse is deferred (only some integrators can ignore it).
Color loadBsdf(const XmlContext &ctx, const pugi::xml_node &node, Deferred &deferred);

/// Where loadShape appends what it reads: the scene's shapes, or a shapegroup's.
struct ShapeLists {
    std::vector<Mesh> &meshes;
    std::vector<Sphere> &spheres;
    std::vector<Disk> &disks;
    std::vector<Cylinder> &cylinders;
};

/// A <shape> (obj, ply, serialized, rectangle, cube, sphere, disk or cylinder) with its bsdf or ref and
/// area emitter, appended to its list in `out`.
void loadShape(const XmlContext &ctx, const pugi::xml_node &node, const Definitions &defs, ShapeLists out,
               Deferred &deferred);

/// Throws at the node unless the mesh's positions are finite and bounded and its normals unit length.
void requireFiniteMesh(const XmlContext &ctx, const pugi::xml_node &node, const Mesh &mesh);

}  // namespace mcval
