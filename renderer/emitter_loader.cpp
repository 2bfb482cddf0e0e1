// The <emitter> elements: Mitsuba's point, constant, spot, directional and area emitters, with their
// parameter names and defaults, and envmap's image; projector is known by name and not modelled.
#include "emitter_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "scene_limits.h"
#include "textures/texture_loader.h"

namespace mcval {

namespace {

/// Mitsuba 3's top-level emitter types that only some integrators read (spot, directional, envmap) or that
/// this renderer does not model (projector); their kind, or false for another type.
bool deferredKind(const std::string &type, EmitterKind &kind) {
    if (type == "spot") kind = EmitterKind::Spot;
    else if (type == "directional") kind = EmitterKind::Directional;
    else if (type == "envmap") kind = EmitterKind::Envmap;
    else if (type == "projector") kind = EmitterKind::Unmodelled;
    else return false;
    return true;
}

/// An emitter placed at p: within the coordinates the renderer traces.
void requireFinitePlacement(const XmlContext &ctx, const pugi::xml_node &node, const Vec3f &p) {
    if (!(std::abs(p.x) <= kMaxCoordinate && std::abs(p.y) <= kMaxCoordinate && std::abs(p.z) <= kMaxCoordinate))
        ctx.fail(node, "the emitter's position must be finite and within " + std::to_string(kMaxCoordinate));
}

/// A nested element: a texture (a textured radiance or intensity; a spot's projected image is read) or anything else.
void noObjects(const XmlContext &ctx, const XmlProps &props) {
    if (props.objects().empty()) return;
    const pugi::xml_node child = props.objects()[0];
    const std::string name = child.attribute("name").as_string();
    if (std::string(child.name()) == "texture" || std::string(child.name()) == "ref")
        ctx.fail(child, "textured emission" + (name.empty() ? std::string() : " (\"" + name + "\")") +
                            " is not modelled, such as an area light's textured radiance: this renderer's emitters "
                            "read an <rgb>, a <float> or a <spectrum> given by its values (and a spot's bitmap or "
                            "checkerboard `texture`)");
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
    const auto &objects = props.objects();
    if (objects.size() == 1 && std::string(objects[0].name()) == "texture" &&
        ctx.propertyName(objects[0]) == "texture" && isModelledTexture(ctx.attr(objects[0], "type")))
        light.texture = loadTexture(ctx, objects[0], kMaxEmission);
    else
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

EnvironmentMap readEnvmap(const XmlContext &ctx, const pugi::xml_node &node, const std::vector<std::string> &folders) {
    XmlProps props(ctx, node);
    EnvironmentMap map;
    const std::string name = props.getStringRequired("filename");
    std::string extension = std::filesystem::path(name).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    if (extension != ".exr")
        props.failAt("filename", "an envmap's image is read from an OpenEXR file (.exr), not \"" + name + "\"");
    try {
        map.image = std::make_shared<const RgbImage>(readRgbImage(XmlContext::resolve(name, folders), false));
    } catch (const std::exception &e) {
        props.failAt("filename", std::string("cannot read the envmap's image: ") + e.what());
    }
    if (map.image->width < 2 || map.image->height < 3)
        props.failAt("filename", "an envmap's image must have at least 2 x 3 pixels, as Mitsuba requires");
    if (const std::string where = badPixel(*map.image, kMaxEmission); !where.empty())
        props.failAt("filename", "the envmap's pixel" + where + " is negative, not finite or above " +
                                     std::to_string(kMaxEmission) + " (a radiance is read)");
    map.scale = props.getFloat("scale", 1.f);
    props.requireRange("scale", map.scale, 0.f, kMaxEmission);
    map.toWorld = props.getTransform("to_world");
    if (!map.toWorld.orthonormal(1e-4))
        props.failAt("to_world", "an envmap's to_world must be a rotation: Mitsuba's directions are not unit under "
                                 "a scale or shear");
    // MIS compensation changes how directions are drawn, not what the image converges to.
    props.ignore("mis_compensation");
    props.finish("filename, scale, to_world, mis_compensation");
    noObjects(ctx, props);
    return map;
}

}  // namespace

void loadEmitter(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred) {
    const std::string type = ctx.attr(node, "type");
    if (EmitterKind kind; deferredKind(type, kind)) {
        deferred.otherEmitters.push_back(
            {node, "<emitter type=\"" + type + "\"> at line " + std::to_string(ctx.line(node)), kind, ctx.folders});
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
        } else if (other.kind == EmitterKind::Envmap) {
            // Mitsuba: "Only one environment emitter can be specified per scene."
            if (scene.environment || scene.envmap)
                ctx.fail(other.node, "only one environment emitter (constant or envmap) is allowed in a scene");
            scene.envmap = readEnvmap(ctx, other.node, other.folders);
        } else {
            ctx.fail(other.node, "the " + chosen + " integrator would be lit by this " +
                                     ctx.attr(other.node, "type") + " emitter, which this renderer does not model "
                                     "(it models point, spot, directional, constant, envmap and area emitters)");
        }
    }
}

}  // namespace mcval
