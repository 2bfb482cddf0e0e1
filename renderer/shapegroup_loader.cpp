#include "shapegroup_loader.h"

#include <string>

#include "disk_cylinder_loader.h"
#include "mesh.h"
#include "sphere_loader.h"

namespace mcval {

namespace {

constexpr uint64_t kMaxInstancedTriangles = uint64_t(1) << 28, kMaxInstancedShapes = uint64_t(1) << 20;

/// The members of a <shape type="shapegroup">, each loaded as a top-level shape would be.
ShapeGroup readGroup(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred) {
    XmlProps props(ctx, node);
    props.finish("no properties (a shapegroup only holds shapes: Mitsuba ignores its to_world; its instances "
                 "place it)");
    ShapeGroup group;
    for (const auto &child : props.objects()) {
        const std::string tag = child.name();
        if (tag == "emitter") ctx.fail(child, "an emitter inside a shapegroup: Mitsuba does not instance emitters");
        if (tag != "shape") ctx.fail(child, "unsupported element in a shapegroup: expected <shape>");
        const std::string type = ctx.attr(child, "type");
        if (type == "shapegroup") ctx.fail(child, "a shapegroup inside a shapegroup: Mitsuba does not nest them");
        if (type == "instance") ctx.fail(child, "an instance inside a shapegroup: Mitsuba does not nest instancing");
        for (const auto &grandchild : child.children("emitter"))
            ctx.fail(grandchild, "a shape with an emitter inside a shapegroup: Mitsuba does not instance emitters");
        loadShape(ctx, child, defs, {group.meshes, group.spheres, group.disks, group.cylinders}, deferred);
    }
    return group;
}

}  // namespace

void loadShapeGroup(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred) {
    ShapeGroup group = readGroup(ctx, node, defs, deferred);
    const std::string id = node.attribute("id") ? ctx.attr(node, "id") : "";
    if (id.empty()) return;  // no instance can place it: checked, and not rendered (as in Mitsuba)
    if (defs.groups.count(id) || defs.bsdfNodes.count(id)) ctx.fail(node, "the id \"" + id + "\" is already defined");
    defs.groups[id] = std::move(group);
}

void loadInstance(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, SceneDescription &scene) {
    XmlProps props(ctx, node);
    const Transform toWorld = props.getTransform("to_world");
    props.finish("to_world");
    // Mitsuba 3.9 fails on a shapegroup inline in an instance, so only a <ref> is read.
    const char *expected = "an instance takes one <ref id=\"...\"> to a shapegroup";
    if (props.objects().size() != 1 || std::string(props.objects()[0].name()) != "ref")
        ctx.fail(props.objects().empty() ? node : props.objects()[0], expected);
    const pugi::xml_node ref = props.objects()[0];
    const std::string id = ctx.attr(ref, "id");
    const auto it = defs.groups.find(id);
    if (it == defs.groups.end()) ctx.fail(ref, "no <shape type=\"shapegroup\" id=\"" + id + "\"> in the file");
    const ShapeGroup *group = &it->second;
    const std::string what = "shapegroup \"" + id + "\"";
    // Flattening copies every member: the copies are bounded as one mesh file's triangles are.
    uint64_t triangles = 0;
    for (const Mesh &member : group->meshes) triangles += member.indices.size() / 3;
    defs.instancedTriangles += triangles;
    defs.instancedShapes += group->meshes.size() + group->spheres.size() + group->disks.size() + group->cylinders.size();
    if (defs.instancedTriangles > kMaxInstancedTriangles || defs.instancedShapes > kMaxInstancedShapes)
        ctx.fail(node, "the instances so far copy " + std::to_string(defs.instancedTriangles) + " triangles and " +
                           std::to_string(defs.instancedShapes) + " shapes: at most 2^28 triangles and 2^20 shapes "
                           "are supported (instances are flattened, each a copy)");
    const std::string suffix = " (instance" + ctx.at(node) + ")";
    for (const Mesh &member : group->meshes) {
        Mesh mesh = transformMesh(member, toWorld);
        requireFiniteMesh(ctx, node, mesh);
        mesh.name += suffix;
        scene.meshes.push_back(std::move(mesh));
    }
    for (const Sphere &member : group->spheres) {
        Sphere sphere;
        // Our sphere is intersected as a sphere, so an instance may not make it an ellipsoid.
        if (const auto refusal = placeSphere(member, toWorld, false, sphere))
            ctx.fail(node, "sphere \"" + member.name + "\" of " + what + " under this instance's to_world: " +
                               refusal->reason);
        sphere.name += suffix;
        scene.spheres.push_back(std::move(sphere));
    }
    // A disk or a cylinder takes any affine map: the instance's composed after its own, normals by the
    // inverse transpose of the product, as Mitsuba transforms an instanced shape's normals.
    const Affine instance = Affine::from(toWorld);
    const auto refuse = [&](const char *kind, const std::string &name, const std::string &why) {
        ctx.fail(node, std::string(kind) + " \"" + name + "\" of " + what + " under this instance's to_world: " + why);
    };
    const auto place = [&](const auto &members, auto &into, const char *kind) {
        for (const auto &member : members) {
            auto shape = member;
            shape.toWorld = instance * member.toWorld;
            if (const auto why = whyUntraceable(shape)) refuse(kind, member.name, *why);
            shape.name += suffix;
            into.push_back(std::move(shape));
        }
    };
    place(group->disks, scene.disks, "disk");
    place(group->cylinders, scene.cylinders, "cylinder");
}

}  // namespace mcval
