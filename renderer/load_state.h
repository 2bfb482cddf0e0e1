// What loading a scene file gathers besides the scene itself: definitions for <ref>s, and elements the chosen
// integrator may not use, judged once it is known.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <pugixml.hpp>

#include "emitters/emitter.h"
#include "scene.h"

namespace mcval {

/// Elements the chosen integrator may not use, judged once the integrator is known.
struct Deferred {
    /// The emitter kinds the chosen integrator reads, once it is known (`known`): a shape's area emitter is
    /// then read where it stands, or kept aside to be skipped with a note.
    EmitterKinds reads;
    bool known = false;
    /// Whether it reads a textured diffuse reflectance (the integrators that read any BSDF), once `known`.
    bool readsTextures = false;
    /// BSDFs whose surfaces are not Lambertian: read (a scattering BSDF, scene_bsdfs.h) or not modelled.
    std::vector<std::pair<pugi::xml_node, std::string>> nonDiffuseBsdfs, unmodelledBsdfs, areaEmitters;
    /// A BSDF with a parameter we cannot read (`given`: a texture, a per-wavelength spectrum, ...): refused
    /// where the integrator reads the reflectance, skipped elsewhere (`what` in the note). `diffuse`: the
    /// parameter is a diffuse BSDF's reflectance.
    struct UnreadReflectance {
        pugi::xml_node node;
        std::string what, given;
        bool diffuse = true;
    };
    std::vector<UnreadReflectance> unreadReflectances;
    /// Diffuse BSDFs whose reflectance is a texture read (bitmap, checkerboard): refused by an integrator that
    /// reads one albedo per surface, skipped by those that read none.
    std::vector<std::pair<pugi::xml_node, std::string>> texturedBsdfs;
    /// Top-level <texture>s: read only through a BSDF (a textured reflectance, or an unread one).
    std::vector<std::pair<pugi::xml_node, std::string>> textures;
    /// Top-level emitters read only by the integrators that declare their kind (spot, directional, envmap), or
    /// by none (projector: Unmodelled): read, refused or skipped with a note once the integrator is known.
    struct OtherEmitter {
        pugi::xml_node node;
        std::string what;
        EmitterKind kind;
        std::vector<std::string> folders;  ///< where the file resolver looked at the element (an envmap's image)
    };
    std::vector<OtherEmitter> otherEmitters;
    /// <medium>s and references to them: no integrator of ours traces media, nor do the Mitsuba integrators
    /// they are compared with (direct, aov), so they are skipped.
    std::vector<std::pair<pugi::xml_node, std::string>> media;
    /// Top-level bsdfs no shape refers to: read by no integrator, whatever their type.
    std::vector<std::pair<pugi::xml_node, std::string>> unreferencedBsdfs;
};

/// A <shape type="shapegroup">'s members, in the group's space: kept aside, rendered only through instances.
struct ShapeGroup {
    std::vector<Mesh> meshes;
    std::vector<Sphere> spheres;
    std::vector<Disk> disks;
    std::vector<Cylinder> cylinders;
};

/// A surface's material as the loader reads it: its BSDF (Mitsuba's diffuse, black from behind, a scattering
/// BSDF of scene_bsdfs.h, or a twosided around them).
using Material = std::shared_ptr<const Bsdf>;

/// What the file defines, for a <ref id>: bsdfs (their material) and shapegroups, which only an instance may
/// refer to. Mitsuba resolves references once the whole file is read, so a <ref> may precede its definition.
struct Definitions {
    std::map<std::string, pugi::xml_node> bsdfNodes;  ///< every <bsdf id> of the file (registerBsdfs)
    std::map<std::string, Material> bsdfs;            ///< those read so far
    BsdfList list = defaultBsdfs();                   ///< the scene's BSDFs, which shapes name by index
    std::map<const Bsdf *, uint32_t> indices;          ///< where each of them is in `list`
    /// The index in `list` of `material` (added the first time): what a shape holds.
    uint32_t indexOf(const Material &material) {
        if (material == list[0]) return 0;
        const auto [it, added] = indices.emplace(material.get(), uint32_t(list.size()));
        if (added) list.push_back(material);
        return it->second;
    }
    std::set<std::string> reading;                    ///< ids being read: a reference back to one is a cycle
    std::map<std::string, ShapeGroup> groups;
    uint64_t instancedTriangles = 0, instancedShapes = 0;  ///< copies made by instances so far (bounded)
};

}  // namespace mcval
