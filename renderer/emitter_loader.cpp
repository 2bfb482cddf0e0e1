// A top-level <emitter>: the point and constant emitters our integrators use, the other types skipped.
#include "emitter_loader.h"

#include <string>

#include "scene_limits.h"

namespace mcval {

namespace {

/// Mitsuba 3's emitter types that none of our integrators uses; each is skipped with a note (and the
/// harness removes them from Mitsuba's scene as well).
bool isOtherEmitter(const std::string &type) {
    return type == "directional" || type == "spot" || type == "projector" || type == "envmap";
}

}  // namespace

void loadEmitter(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred) {
    const std::string type = ctx.attr(node, "type");
    if (isOtherEmitter(type)) {
        deferred.otherEmitters.emplace_back(node, "<emitter type=\"" + type + "\"> at line " +
                                                      std::to_string(ctx.line(node)));
        return;
    }
    XmlProps props(ctx, node);
    if (type == "point") {
        PointLight light;
        // Mitsuba places a point light by `position` or by `to_world` (its origin), not both.
        const bool placed = props.has("to_world");
        if (placed && props.has("position")) ctx.fail(node, "a point light takes position or to_world, not both");
        light.position = placed ? props.getTransform("to_world").point({0.f, 0.f, 0.f})
                                : props.getPoint("position", {0.f, 0.f, 0.f});
        props.requireRange(placed ? "to_world" : "position", light.position, -kMaxCoordinate, kMaxCoordinate);
        light.intensity = props.getColor("intensity", {1.f, 1.f, 1.f});
        props.requireRange("intensity", light.intensity, 0.f, kMaxEmission);
        props.finish("position or to_world, intensity");
        scene.pointLights.push_back(light);
    } else if (type == "constant") {
        if (scene.environment) ctx.fail(node, "only one constant emitter is supported");
        scene.environment = props.getColor("radiance", {1.f, 1.f, 1.f});
        props.requireRange("radiance", *scene.environment, 0.f, kMaxEmission);
        props.finish("radiance");
    } else {
        ctx.fail(node, "unsupported emitter type \"" + type +
                           "\": expected point or constant (directional, spot, projector and envmap are skipped)");
    }
    if (!props.objects().empty()) ctx.fail(props.objects()[0], "unexpected element inside <emitter>");
}

}  // namespace mcval
