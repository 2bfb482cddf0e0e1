// Shapes and their materials in a scene file: meshes, exact shapes, bsdfs and area emitters.
#pragma once

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

/// Throws at the node unless p is finite and within kMaxCoordinate; `what` names p in the message.
void requirePosition(const XmlContext &ctx, const pugi::xml_node &node, const std::string &what, const Vec3f &p);

/// A <bsdf>'s reflectance; a type other than diffuse is deferred (only some integrators can ignore it).
Color loadBsdf(const XmlContext &ctx, const pugi::xml_node &node, Deferred &deferred);

/// A <shape> (obj, ply, rectangle, cube, sphere, disk or cylinder) with its bsdf or ref and area
/// emitter, appended to the scene's meshes, spheres, disks or cylinders.
void loadShape(const XmlContext &ctx, const pugi::xml_node &node, const std::map<std::string, Color> &bsdfs,
               SceneDescription &scene, Deferred &deferred);

}  // namespace mcval
