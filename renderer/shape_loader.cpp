#include "shape_loader.h"

#include "bsdfs/textured_bsdf.h"

#include <climits>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "disk_cylinder_loader.h"
#include "emitter_loader.h"
#include "error.h"
#include "mesh.h"
#include "scene_limits.h"
#include "sphere_loader.h"

namespace mcval {

namespace {

namespace fs = std::filesystem;

std::string typeOf(const XmlContext &ctx, const pugi::xml_node &node) { return ctx.attr(node, "type"); }

/// Whether a <ref> names a shape's medium (Mitsuba's interior and exterior) rather than its bsdf.
bool isMediumSlot(const pugi::xml_node &ref) {
    const std::string name = ref.attribute("name").value();
    return name == "interior" || name == "exterior";
}

bool inRange(const Vec3f &p, float bound) {
    return std::abs(p.x) <= bound && std::abs(p.y) <= bound && std::abs(p.z) <= bound;  // false for NaN
}

/// What a shape holds besides its geometry: its material and, where the integrator reads it, its area emitter.
struct ShapeChildren {
    Material material;
    std::optional<Color> areaRadiance;
};

/// The shape's one <bsdf> or <ref> (its material; without one Mitsuba's default, black where the shape emits)
/// and its area emitter (read where the integrator reads area emitters, kept aside to be judged otherwise) and
/// media, whatever the shape.
ShapeChildren loadShapeChildren(const XmlContext &ctx, const XmlProps &props, Definitions &defs, Deferred &deferred) {
    ShapeChildren out;
    Material &material = out.material;
    material = defaultBsdf();
    bool hasBsdf = false;
    for (const auto &child : props.objects()) {
        const std::string tag = child.name();
        if (tag == "emitter") {
            if (typeOf(ctx, child) != "area") ctx.fail(child, "a shape's emitter must be of type \"area\"");
            if (deferred.known && deferred.reads.has(EmitterKind::Area)) {
                if (out.areaRadiance) ctx.fail(child, "a shape takes one area emitter");
                out.areaRadiance = readAreaRadiance(ctx, child);
            } else {
                deferred.areaEmitters.emplace_back(child, "<emitter type=\"area\"> at line " +
                                                              std::to_string(ctx.line(child)));
            }
            continue;
        }
        // The media on either side of the surface (interior, exterior), inline or by reference.
        if (tag == "medium" || (tag == "ref" && isMediumSlot(child))) {
            deferred.media.emplace_back(child, "<" + tag + " name=\"" + std::string(child.attribute("name").value()) +
                                                   "\"> at line " + std::to_string(ctx.line(child)));
            continue;
        }
        if (hasBsdf && (tag == "bsdf" || tag == "ref")) ctx.fail(child, "a shape takes one bsdf");
        if (tag == "bsdf") {
            material = loadBsdf(ctx, child, defs, deferred);
        } else if (tag == "ref") {
            material = resolveBsdfRef(ctx, child, defs, deferred);
        } else {
            ctx.fail(child, "unsupported element in <shape>: expected <bsdf>, <ref>, <emitter type=\"area\"> or "
                            "<medium>");
        }
        hasBsdf = true;
    }
    if (!hasBsdf && out.areaRadiance) material = defaultEmitterBsdf();
    return out;
}

/// A textured material needs the surface's (u, v): this renderer has them on meshes with texture coordinates.
void requireTexcoords(const XmlContext &ctx, const pugi::xml_node &node, const Material &material, bool has) {
    const auto *textured = dynamic_cast<const TexturedBsdf *>(material.get());
    if (has || !textured || !textured->readsUv()) return;
    ctx.fail(node, "a textured bsdf needs the surface's texture coordinates, which this renderer reads from an OBJ's "
                   "vt lines and a rectangle's corners, not from a " + ctx.attr(node, "type"));
}

/// An exact shape (sphere, disk, cylinder), already read from `props`, with its name and its bsdf's
/// reflectance, appended to `list`.
template <typename Shape>
void appendExact(std::vector<Shape> &list, Shape shape, const std::string &name, const XmlContext &ctx,
                 const XmlProps &props, Definitions &defs, Deferred &deferred) {
    shape.name = name;
    const ShapeChildren children = loadShapeChildren(ctx, props, defs, deferred);
    requireTexcoords(ctx, props.element(), children.material, false);
    shape.bsdf = defs.indexOf(children.material);
    shape.areaRadiance = children.areaRadiance;
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

void loadShape(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, ShapeLists out,
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
    const ShapeChildren children = loadShapeChildren(ctx, props, defs, deferred);
    requireTexcoords(ctx, node, children.material, !mesh.texcoords.empty());
    mesh.bsdf = defs.indexOf(children.material);
    mesh.areaRadiance = children.areaRadiance;
    out.meshes.push_back(std::move(mesh));
}

}  // namespace mcval
