// The <emitter> elements: Mitsuba's point, constant, spot, directional and area emitters, with their
// parameter names and defaults; projector and envmap are known by name and not modelled.
#include "emitter_loader.h"

#include <cmath>
#include <string>

#include "scene_limits.h"

namespace mcval {

namespace {

/// Mitsuba 3's top-level emitter types that only some integrators read (spot, directional) or that this
/// renderer does not model (projector, envmap); their kind, or false for another type.
bool deferredKind(const std::string &type, EmitterKind &kind) {
    if (type == "spot") kind = EmitterKind::Spot;
    else if (type == "directional") kind = EmitterKind::Directional;
    else if (type == "projector" || type == "envmap") kind = EmitterKind::Unmodelled;
    else return false;
    return true;
}

/// An emitter placed at p: within the coordinates the renderer traces.
void requireFinitePlacement(const XmlContext &ctx, const pugi::xml_node &node, const Vec3f &p) {
    if (!(std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate && std::abs(p.z) <= kMaxCoordinate))
        ctx.fail(node, "the emitter's position must be finite and within " + std::to_string(kMaxCoordinate));
}

/// A nested element: a texture (a spot's projected image, a textured radiance) or anything else.
void noObjects(const XmlContext &ctx, const XmlProps &props) {
    if (props.objects().empty()) return;
    const pugi::xml_node child = props.objects()[0];
    const std::string name = child.attribute("name").as_string();
    if (std::string(child.name()) == "texture" || std::string(child.name()) == "ref")
        ctx.fail(child, "textured emission" + (name.empty() ? std::string() : " (\"" + name + "\")") +
                            " is not modelled, such as a spot light's projected image: this renderer's emitters "
                            "read an <rgb>, a <float> or a <spectrum> given by its values");
    ctx.fail(child, "unexpected element inside <emitter>");
}

SpotLight readSpot(const XmlContext &ctx, const pugi::xml_node &node) {
    XmlProps props(ctx, node);
    SpotLight light;
    light.toWorld = props.getTransform("to_world");
    requireFinitePlacement(ctx, node, light.toWorld.point({0.f, 0.f, 0.f}));
    light.intensity = props.getColor("intensity", {1.f, 1.f, 1.f});
    props.requireRange("intensity", light.intensity, 0.f, kMaxEmission);
    light.cutoffAngle = props.getFloat("cutoff_angle", 20.f);
    props.requireRange("cutoff_angle", light.cutoffAngle, 1e-3f, 180.f);
    light.beamWidth = props.getFloat("beam_width", light.cutoffAngle * 3.f / 4.f);
    // Mitsuba asserts beam_width <= cutoff_angle: the falloff runs from one to the other.
    props.requireRange("beam_width", light.beamWidth, 0.f, light.cutoffAngle);
    props.finish("intensity, cutoff_angle, beam_width, to_world");
    noObjects(ctx, props);
    return light;
}

DirectionalLight readDirectional(const XmlContext &ctx, const pugi::xml_node &node) {
    XmlProps props(ctx, node);
    DirectionalLight light;
    // Mitsuba takes direction or to_world (its +z), not both.
    if (props.has("direction") && props.has("to_world"))
        ctx.fail(node, "a directional light takes direction or to_world, not both");
    const Vec3f d = props.has("direction") ? props.getPoint("direction", {0.f, 0.f, 1.f})
                                           : props.getTransform("to_world").vector({0.f, 0.f, 1.f});
    const float length = norm(d);
    if (!(length > 0.f) || !std::isfinite(length))
        ctx.fail(node, "a directional light needs a finite, non-zero direction");
    light.direction = d / length;
    light.irradiance = props.getColor("irradiance", {1.f, 1.f, 1.f});
    props.requireRange("irradiance", light.irradiance, 0.f, kMaxEmission);
    props.finish("irradiance, direction or to_world");
    noObjects(ctx, props);
    return light;
}

}  // namespace

void loadEmitter(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred) {
    const std::string type = ctx.attr(node, "type");
    if (EmitterKind kind; deferredKind(type, kind)) {
        deferred.otherEmitters.push_back(
            {node, "<emitter type=\"" + type + "\"> at line " + std::to_string(ctx.line(node)), kind});
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
    noObjects(ctx, props);
}

Color readAreaRadiance(const XmlContext &ctx, const pugi::xml_node &node) {
    XmlProps props(ctx, node);
    const Color radiance = props.getColor("radiance", {1.f, 1.f, 1.f});
    props.requireRange("radiance", radiance, 0.f, kMaxEmission);
    props.finish("radiance");
    noObjects(ctx, props);
    return radiance;
}

void judgeOtherEmitters(const XmlContext &ctx, const Deferred &deferred, const std::string &chosen,
                        SceneDescription &scene, std::vector<std::string> &skipped) {
    for (const auto &other : deferred.otherEmitters) {
        if (!deferred.reads.has(other.kind)) {
            skipped.push_back(other.what);
        } else if (other.kind == EmitterKind::Spot) {
            scene.spotLights.push_back(readSpot(ctx, other.node));
        } else if (other.kind == EmitterKind::Directional) {
            scene.directionalLights.push_back(readDirectional(ctx, other.node));
        } else {
            ctx.fail(other.node, "the " + chosen + " integrator would be lit by this " +
                                     ctx.attr(other.node, "type") + " emitter, which this renderer does not model "
                                     "(it models point, spot, directional, constant and area emitters)");
        }
    }
}

}  // namespace mcval
