#include "sensor_loader.h"

#include <cmath>
#include <cstdlib>
#include <string>

#include "film_loader.h"
#include "scene_limits.h"
#include "shape_loader.h"

namespace mcval {

namespace {

std::string typeOf(const XmlContext &ctx, const pugi::xml_node &node) { return ctx.attr(node, "type"); }

/// Mitsuba refuses a camera whose to_world scales or shears (Transform::has_scale: its columns are
/// orthonormal within 1e-3), and a scaled camera's rays would not be unit length (at 1e-30 they are 0).
void requireRigid(const XmlContext &ctx, const pugi::xml_node &node, const Transform &t) {
    if (!t.orthonormal(1e-3))
        ctx.fail(node, "the camera's to_world scales or shears (its axes must be orthonormal, as Mitsuba "
                       "requires): move the scale to the shapes");
}

/// Mitsuba's alternative to fov (and its default, 50mm): a focal length in 35 mm film equivalent, which
/// sets the field of view, in degrees, along the film's diagonal (36 x 24 mm).
float focalLengthFov(XmlProps &props) {
    const std::string text = props.getString("focal_length", "50mm");
    const std::string number = text.size() > 2 && text.compare(text.size() - 2, 2, "mm") == 0
                                   ? text.substr(0, text.size() - 2) : text;
    char *end = nullptr;
    const double focal = std::strtod(number.c_str(), &end);
    if (number.empty() || *end != '\0' || !(focal > 0.0 && focal < 1e6))
        props.failAt("focal_length", "expected a focal length in millimetres such as \"50mm\", got \"" + text + "\"");
    const float fov = float(2.0 * std::atan(std::sqrt(36.0 * 36.0 + 24.0 * 24.0) / (2.0 * focal)) * 180.0 / M_PI);
    props.requireRange("focal_length", fov, kMinFov, kMaxFov);
    return fov;
}

/// The perspective camera's own properties: fov (or focal_length), fov_axis, focus_distance.
void loadPerspective(const XmlContext &ctx, const pugi::xml_node &node, XmlProps &props, CameraSpec &cam) {
    if (props.has("fov")) {
        cam.fov = props.getFloatRequired("fov");
        props.requireRange("fov", cam.fov, kMinFov, kMaxFov);
        cam.fovAxis = props.getString("fov_axis", "x");
    } else {
        if (props.has("fov_axis")) props.failAt("fov_axis", "fov_axis goes with fov, not with a focal length");
        cam.fov = focalLengthFov(props);
        cam.fovAxis = "diagonal";
    }
    if (cam.fovAxis != "x" && cam.fovAxis != "y" && cam.fovAxis != "diagonal" && cam.fovAxis != "smaller" &&
        cam.fovAxis != "larger")
        ctx.fail(node, "fov_axis must be x, y, diagonal, smaller or larger");
    props.ignore("focus_distance");  // a pinhole has no focus: accepted and ignored
    // Bounded so that the view stays within a few films of the axis (exporters write 0).
    cam.principalOffsetX = props.getFloat("principal_point_offset_x", 0.f);
    cam.principalOffsetY = props.getFloat("principal_point_offset_y", 0.f);
    props.requireRange("principal_point_offset_x", cam.principalOffsetX, -kMaxPrincipalOffset, kMaxPrincipalOffset);
    props.requireRange("principal_point_offset_y", cam.principalOffsetY, -kMaxPrincipalOffset, kMaxPrincipalOffset);
}

/// An orthographic camera's to_world may scale and shear (its scale sizes the view, as in Mitsuba), but
/// not collapse: its image of the [-1, 1]^2 square must have an area and its +z a length.
void requireOrthographicFrame(const XmlContext &ctx, const pugi::xml_node &node, const Transform &t) {
    if (isDegenerate(Affine::from(t)))
        ctx.fail(node, "the orthographic camera's to_world is degenerate (a zero scale, or axes that (nearly) "
                       "coincide): its view would have no area or no direction");
}

/// Every corner of the orthographic camera's near-plane rectangle (the film's aspect known) in bounds.
void requireOrthographicCorners(const XmlContext &ctx, const pugi::xml_node &node, const SceneDescription &scene) {
    const float aspect = float(scene.film.width) / float(scene.film.height);
    for (const float x : {-1.f, 1.f})
        for (const float y : {-1.f, 1.f})
            requirePosition(ctx, node, "a corner of the orthographic camera's view (its to_world)",
                            scene.camera.toWorld.point({x, y / aspect, scene.camera.nearClip}));
}

/// The sensor's <sampler>: its kind and sample_count. Mitsuba's stratified kinds become our sobol (stratified
/// too); the seed and a kind's own knobs change the noise, never the expectation, and are accepted unread.
void loadSampler(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene) {
    const std::string type = typeOf(ctx, node);
    const auto kind = samplerFromFile(type);
    if (!kind)
        ctx.fail(node, "unsupported sampler type \"" + type + "\": expected independent, stratified, multijitter, "
                       "orthogonal, ldsampler or sobol");
    scene.sampler = *kind;
    XmlProps props(ctx, node);
    scene.sampleCount = props.getInt("sample_count", 4);
    props.requireRange("sample_count", scene.sampleCount, 1, kMaxSampleCount);
    props.ignore("seed");
    const bool jitters = type == "stratified" || type == "multijitter" || type == "orthogonal";
    if (jitters) props.ignore("jitter");
    if (type == "orthogonal") props.ignore("strength");
    props.finish(std::string("sample_count, seed") + (jitters ? ", jitter" : "") +
                 (type == "orthogonal" ? ", strength" : ""));
    if (!props.objects().empty()) ctx.fail(props.objects()[0], "unexpected element inside <sampler>");
}

}  // namespace

void loadSensor(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred) {
    const std::string type = typeOf(ctx, node);
    if (type != "perspective" && type != "orthographic")
        ctx.fail(node, "unsupported sensor type: expected \"perspective\" or \"orthographic\"");
    const bool orthographic = type == "orthographic";
    XmlProps props(ctx, node);
    CameraSpec &cam = scene.camera;
    cam.projection = orthographic ? CameraSpec::Projection::Orthographic : CameraSpec::Projection::Perspective;
    if (!orthographic) loadPerspective(ctx, node, props, cam);
    cam.nearClip = props.getFloat("near_clip", 1e-2f);
    cam.farClip = props.getFloat("far_clip", 1e4f);
    if (!(cam.nearClip > 0.f && cam.farClip > cam.nearClip)) ctx.fail(node, "need 0 < near_clip < far_clip");
    cam.toWorld = props.getTransform("to_world");
    requirePosition(ctx, node, "the camera (its to_world)", cam.toWorld.point({0.f, 0.f, 0.f}));
    if (orthographic)
        requireOrthographicFrame(ctx, node, cam.toWorld);
    else
        requireRigid(ctx, node, cam.toWorld);
    props.finish(orthographic ? "near_clip, far_clip, to_world"
                              : "fov, fov_axis, focal_length, near_clip, far_clip, focus_distance, "
                                "principal_point_offset_x, principal_point_offset_y, to_world");
    for (const auto &child : props.objects()) {
        const std::string tag = child.name();
        if (tag == "film") {
            loadFilm(ctx, child, scene.film);
        } else if (tag == "sampler") {
            loadSampler(ctx, child, scene);
        } else if (tag == "medium" || tag == "ref") {  // the medium the camera sits in
            deferred.media.emplace_back(child, "<" + tag + "> in the sensor at line " + std::to_string(ctx.line(child)));
        } else {
            ctx.fail(child, "unsupported element in <sensor>: expected <film>, <sampler> or <medium>");
        }
    }
    if (orthographic) requireOrthographicCorners(ctx, node, scene);
}

}  // namespace mcval
