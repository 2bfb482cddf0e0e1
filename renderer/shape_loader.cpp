#include "shape_loader.h"

#include <climits>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "disk_cylinder_loader.h"
#include "error.h"
#include "mesh.h"
#include "scene_limits.h"
#include "sphere_loader.h"

namespace mcval {

namespace {

namespace fs = std::filesystem;

std::string typeOf(const XmlContext &ctx, const pugi::xml_node &node) { return ctx.attr(node, "type"); }

bool inRange(const Vec3f &p, float bound) {
    return std::abs(p.x) <= bound && std::abs(p.y) <= bound && std::abs(p.z) <= bound;  // false for NaN
}

/// The shape's one <bsdf> or <ref> (its reflectance; the default without one) and its area emitter,
/// whatever the shape.
Color loadShapeChildren(const XmlContext &ctx, const XmlProps &props, const Definitions &defs, Deferred &deferred) {
    Color reflectance{0.5f, 0.5f, 0.5f};
    bool hasBsdf = false;
    for (const auto &child : props.objects()) {
        const std::string tag = child.name();
        if (tag == "emitter") {
            if (typeOf(ctx, child) != "area") ctx.fail(child, "a shape's emitter must be of type \"area\"");
            deferred.areaEmitters.emplace_back(child, "<emitter type=\"area\"> at line " +
                                                          std::to_string(ctx.line(child)));
            continue;
        }
        if (hasBsdf && (tag == "bsdf" || tag == "ref")) ctx.fail(child, "a shape takes one bsdf");
        if (tag == "bsdf") {
            reflectance = loadBsdf(ctx, child, deferred);
        } else if (tag == "ref") {
            const std::string id = ctx.attr(child, "id");
            if (defs.groups.count(id))
                ctx.fail(child, "<ref id=\"" + id + "\"> names a shapegroup: only a <shape type=\"instance\"> "
                                "may refer to one");
            const auto it = defs.bsdfs.find(id);
            if (it == defs.bsdfs.end()) ctx.fail(child, "no <bsdf id=\"" + id + "\"> defined before this point");
            reflectance = it->second;
        } else {
            ctx.fail(child, "unsupported element in <shape>: expected <bsdf>, <ref> or <emitter type=\"area\">");
        }
        hasBsdf = true;
    }
    return reflectance;
}

/// An exact shape (sphere, disk, cylinder), already read from `props`, with its name and its bsdf's
/// reflectance, appended to `list`.
template <typename Shape>
void appendExact(std::vector<Shape> &list, Shape shape, const std::string &name, const XmlContext &ctx,
                 const XmlProps &props, const Definitions &defs, Deferred &deferred) {
    shape.name = name;
    shape.reflectance = loadShapeChildren(ctx, props, defs, deferred);
    list.push_back(std::move(shape));
}

}  // namespace

// Positions finite and bounded, normals unit length, after to_world: what Embree and the integrators
// can trace without producing NaN.
void requireFiniteMesh(const XmlContext &ctx, const pugi::xml_node &node, const Mesh &mesh) {
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        requirePosition(ctx, node, "vertex " + std::to_string(i) + " (after to_world)", mesh.positions[i]);
    for (size_t i = 0; i < mesh.normals.size(); ++i)
        if (!(std::abs(squaredNorm(mesh.normals[i]) - 1.f) < 1e-3f))
            ctx.fail(node, "the normal of vertex " + std::to_string(i) + " is zero or not finite (after to_world)");
}

void requirePosition(const XmlContext &ctx, const pugi::xml_node &node, const std::string &what, const Vec3f &p) {
    if (inRange(p, kMaxCoordinate)) return;
    std::ostringstream msg;
    msg << what << " lies at (" << p.x << ", " << p.y << ", " << p.z << "): coordinates must be finite and within "
        << kMaxCoordinate;
    ctx.fail(node, msg.str());
}

Color loadBsdf(const XmlContext &ctx, const pugi::xml_node &node, Deferred &deferred) {
    const std::string type = typeOf(ctx, node);
    const std::string at = " at line " + std::to_string(ctx.line(node));
    // Every integrator of ours reads the shading normal, which these perturb (Mitsuba's sh_normal shows it).
    if (type == "bumpmap" || type == "normalmap")
        ctx.fail(node, "a <bsdf type=\"" + type + "\"> perturbs the shading normal, which every integrator here "
                       "reads and this renderer does not model");
    if (type != "diffuse") {
        // Only `normals` can ignore it; whether that is allowed is decided when the integrator is known.
        deferred.nonDiffuseBsdfs.emplace_back(node, "<bsdf type=\"" + type + "\">" + at);
        return {0.5f, 0.5f, 0.5f};
    }
    XmlProps props(ctx, node);
    // A reflectance given as a texture (inline or by <ref>) or per wavelength: whether it may go unread is
    // decided when the integrator is known.
    std::string unread;
    for (const auto &child : props.objects())
        if (std::string(child.name()) == "texture" || std::string(child.name()) == "ref")
            unread = "a <" + std::string(child.name()) + "> at line " + std::to_string(ctx.line(child));
    const pugi::xml_node given = props.node("reflectance");
    if (given && std::string(given.name()) == "spectrum" && isPerWavelength(given))
        unread = "a per-wavelength <spectrum> at line " + std::to_string(ctx.line(given));
    if (!unread.empty()) {
        deferred.unreadReflectances.push_back({node, "<bsdf type=\"diffuse\">" + at + " (reflectance: " + unread + ")",
                                               unread});
        return {0.5f, 0.5f, 0.5f};
    }
    const Color rho = props.getColor("reflectance", {0.5f, 0.5f, 0.5f});
    props.requireRange("reflectance", rho, 0.f, 1.f);
    props.finish("reflectance");
    if (!props.objects().empty()) ctx.fail(props.objects()[0], "unexpected element inside <bsdf>");
    return rho;
}

void loadShape(const XmlContext &ctx, const pugi::xml_node &node, const Definitions &defs, ShapeLists out,
               Deferred &deferred) {
    const std::string type = typeOf(ctx, node);
    XmlProps props(ctx, node);
    const Transform toWorld = props.getTransform("to_world");
    const std::string name =
        node.attribute("id") ? ctx.attr(node, "id") : type + " at line " + std::to_string(ctx.line(node));
    if (type == "sphere") return appendExact(out.spheres, loadSphere(props, toWorld), name, ctx, props, defs, deferred);
    if (type == "disk") return appendExact(out.disks, loadDisk(props, toWorld), name, ctx, props, defs, deferred);
    if (type == "cylinder")
        return appendExact(out.cylinders, loadCylinder(props, toWorld), name, ctx, props, defs, deferred);
    Mesh mesh;
    if (type == "obj" || type == "ply") {
        const std::string filename = props.getStringRequired("filename");
        const bool faceNormals = props.getBool("face_normals", false);
        props.finish("filename, face_normals, to_world");
        const fs::path path = ctx.resolve(filename);
        try {
            mesh = loadMeshFile(path.string(), toWorld, faceNormals);
        } catch (const SceneError &e) {
            ctx.fail(node, e.what());
        }
    } else if (type == "serialized") {
        const std::string filename = props.getStringRequired("filename");
        const int shapeIndex = props.getInt("shape_index", 0);
        props.requireRange("shape_index", shapeIndex, 0, INT_MAX);
        const bool faceNormals = props.getBool("face_normals", false);
        const bool flipNormals = props.getBool("flip_normals", false);
        props.finish("filename, shape_index, face_normals, flip_normals, to_world");
        const fs::path path = ctx.resolve(filename);
        try {
            mesh = loadSerializedFile(path.string(), uint32_t(shapeIndex), toWorld, faceNormals, flipNormals);
        } catch (const SceneError &e) {
            ctx.fail(node, e.what());
        }
    } else if (type == "rectangle" || type == "cube") {
        props.finish("to_world");
        mesh = type == "rectangle" ? makeRectangle(toWorld) : makeCube(toWorld);
    } else {
        // Every integrator sees every shape: leaving one out would change any image.
        ctx.fail(node, "unsupported shape type \"" + type +
                           "\" (every integrator sees it, so it cannot be left out): expected obj, ply, serialized, "
                           "rectangle, cube, sphere, disk or cylinder (or shapegroup and instance)");
    }
    requireFiniteMesh(ctx, node, mesh);
    mesh.name = name;
    mesh.reflectance = loadShapeChildren(ctx, props, defs, deferred);
    out.meshes.push_back(std::move(mesh));
}

}  // namespace mcval
