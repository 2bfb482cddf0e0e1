// The Mitsuba 3 XML subset the renderer reads (see docs/ARCHITECTURE.md): what the chosen integrator
// needs is read and checked, what it does not use is skipped with a note, anything else is an error.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "emitter_loader.h"
#include "error.h"
#include "scene_limits.h"
#include "mesh.h"
#include "scene.h"
#include "scene_files.h"
#include "sensor_loader.h"
#include "shape_loader.h"
#include "shapegroup_loader.h"
#include "xml_props.h"
#include "integrators/registry.h"

namespace mcval {

namespace {

namespace fs = std::filesystem;

std::string typeOf(const XmlContext &ctx, const pugi::xml_node &node) { return ctx.attr(node, "type"); }

/// The file's integrator: its type from the registry, its properties parsed by the integrator itself.
void loadIntegrator(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene) {
    const std::string type = typeOf(ctx, node);
    const IntegratorInfo *info = findIntegrator(type);
    if (!info) ctx.fail(node, "unsupported integrator type \"" + type + "\": expected " + integratorNameList());
    XmlProps props(ctx, node);
    scene.integrator.make = info->parse(&props);
    scene.integrator.type = type;
}

/// The integrator whose image a file's <integrator> renders: itself, or the first it wraps if it is Mitsuba's
/// `moment` (which adds the second moment of each pixel beside that integrator's image).
pugi::xml_node imageIntegrator(const XmlContext &ctx, pugi::xml_node node) {
    while (typeOf(ctx, node) == "moment") {
        const pugi::xml_node nested = node.child("integrator");
        if (!nested) ctx.fail(node, "a moment integrator wraps another <integrator>, and this one wraps none");
        node = nested;
    }
    return node;
}

/// The `hide_emitters` of the file's integrator or of one nested in it (`moment`, `aov`), if given.
std::optional<bool> fileHideEmitters(const XmlContext &ctx, const pugi::xml_node &integrator) {
    const pugi::xml_node flag = integrator.find_node([&ctx](const pugi::xml_node &n) {
        return std::string(n.name()) == "boolean" && ctx.propertyName(n) == "hide_emitters";
    });
    if (!flag) return std::nullopt;
    return XmlProps(ctx, flag.parent()).getBool("hide_emitters", true);
}

/// A top-level element of Nori's dialect (<camera>, <mesh>, a <sampler> outside the sensor).
[[noreturn]] void failNoriDialect(const XmlContext &ctx, const pugi::xml_node &node) {
    ctx.fail(node, "this is Nori's scene dialect, not Mitsuba 3's: the harness translates it for every engine "
                   "(python -m harness images --scene FILE)");
}

/// What the walk over a scene's elements gathers (the scene file's and its includes'). Bsdfs and shapes are
/// read after it, once every <bsdf id> a <ref> may name is known.
struct Walk {
    Walk(SceneDescription &s, const std::string &i) : scene(s), integrator(i) {}
    SceneDescription &scene;
    const std::string &integrator;  ///< the caller's, overriding the file's; empty: the file's
    Definitions defs;
    std::vector<pugi::xml_node> bsdfs;
    /// Each top-level shape with the file resolver's folders where it stood (an index into folderLists).
    std::vector<std::pair<pugi::xml_node, size_t>> shapes;
    std::vector<std::vector<std::string>> folderLists;
    std::vector<pugi::xml_node> instances;
    bool hasSensor = false, hasIntegrator = false;
    Deferred deferred;
};

/// The shapes the walk set aside, in document order, each shape's files looked for where it stood (a bsdf is
/// read when a shape refers to it); then the instances, whose <ref> may name a shapegroup further down.
void loadSetAside(XmlContext &ctx, Walk &w) {
    for (const auto &[node, folders] : w.shapes) {
        ctx.folders = w.folderLists[folders];
        const std::string type = typeOf(ctx, node);
        if (type == "shapegroup") loadShapeGroup(ctx, node, w.defs, w.deferred);
        else if (type == "instance") w.instances.push_back(node);
        else loadShape(ctx, node, w.defs, {w.scene.meshes, w.scene.spheres, w.scene.disks, w.scene.cylinders},
                       w.deferred);
    }
    for (const pugi::xml_node &node : w.instances) loadInstance(ctx, node, w.defs, w.scene);
    for (const pugi::xml_node &node : w.bsdfs)
        if (const std::string id = ctx.attr(node, "id"); !w.defs.bsdfs.count(id))
            w.deferred.unreferencedBsdfs.emplace_back(node, "<bsdf id=\"" + id + "\"> at line " +
                                                                std::to_string(ctx.line(node)) + " (no shape refers to it)");
}

/// The elements under `parent` (the <scene> of a file in `chain`, the outermost first), in document order:
/// an <include> walks its file's elements where it stands, a <path> is searched from there on.
void walkElements(XmlContext &ctx, const pugi::xml_node &parent, Walk &w, const std::vector<std::string> &chain) {
    for (pugi::xml_node node : parent.children()) {
        if (node.type() != pugi::node_element) continue;
        const std::string tag = node.name();
        if (tag == "default") {
            // The scene file's were read first; an included file's count where not given already.
            if (chain.size() > 1 && !node.attribute("name").empty())
                ctx.params.emplace(node.attribute("name").value(), node.attribute("value").value());
        } else if (tag == "path") {
            addPath(ctx, node);
        } else if (tag == "include") {
            std::vector<std::string> inner = chain;
            walkElements(ctx, includeFile(ctx, node, inner), w, inner);
        } else if (tag == "sensor") {
            if (w.hasSensor) ctx.fail(node, "only one sensor is supported");
            loadSensor(ctx, node, w.scene, w.deferred);
            w.hasSensor = true;
        } else if (tag == "shape") {
            registerBsdfs(ctx, node, w.defs);
            if (w.folderLists.empty() || w.folderLists.back() != ctx.folders) w.folderLists.push_back(ctx.folders);
            w.shapes.emplace_back(node, w.folderLists.size() - 1);
        } else if (tag == "bsdf") {
            if (ctx.attr(node, "id").empty()) ctx.fail(node, "a top-level <bsdf> needs an id to be referenced by");
            registerBsdfs(ctx, node, w.defs);
            w.bsdfs.push_back(node);
        } else if (tag == "medium") {
            w.deferred.media.emplace_back(node, "<medium> at line " + std::to_string(ctx.line(node)));
        } else if (tag == "emitter") {
            loadEmitter(ctx, node, w.scene, w.deferred);
        } else if (tag == "texture") {
            w.deferred.textures.emplace_back(node, "<texture> at line " + std::to_string(ctx.line(node)));
        } else if (tag == "integrator") {
            if (w.hasIntegrator) ctx.fail(node, "only one integrator is supported");
            // An integrator given by the caller overrides the file's, whatever its type; the file's
            // parameters are read only when it names the same integrator. The caller asked for the
            // override, so it needs no note.
            const pugi::xml_node own = imageIntegrator(ctx, node);
            if (w.integrator.empty() || typeOf(ctx, own) == w.integrator) loadIntegrator(ctx, own, w.scene);
            w.scene.hideEmitters = fileHideEmitters(ctx, node);
            w.hasIntegrator = true;
        } else if (tag == "camera" || tag == "mesh" || tag == "sampler") {
            failNoriDialect(ctx, node);
        } else {
            ctx.fail(node, "unsupported element: expected <default>, <path>, <include>, <sensor>, <shape>, <bsdf>, "
                           "<texture>, <emitter>, <medium> or <integrator>");
        }
    }
}

}  // namespace

SceneDescription loadScene(const std::string &path, const std::map<std::string, std::string> &params,
                           const std::string &integrator) {
    XmlContext ctx;
    ctx.file = path;
    ctx.text = readSceneFile(path);

    pugi::xml_document doc;
    parseSceneText(doc, ctx.text, path);
    const pugi::xml_node root = doc.document_element();
    if (std::string(root.name()) != "scene") ctx.fail(root, "the root element must be <scene>");
    for (const char *nori : {"camera", "mesh"})  // Nori's files have no version: say what they are instead
        if (const pugi::xml_node node = root.child(nori)) failNoriDialect(ctx, node);
    if (!root.attribute("version")) ctx.fail(root, "missing version attribute, e.g. version=\"3.0.0\"");

    // <default> values first (Mitsuba takes them in document order, before use), then overrides.
    for (pugi::xml_node node : root.children("default")) {
        const std::string name = node.attribute("name").value();
        if (name.empty() || !node.attribute("value")) ctx.fail(node, "expected name=\"...\" and value=\"...\"");
        ctx.params[name] = node.attribute("value").value();
    }
    for (const auto &[k, v] : params) ctx.params[k] = v;
    ctx.folders = {fs::path(path).parent_path().string()};

    SceneDescription scene;
    scene.file = path;
    Walk w(scene, integrator);
    std::error_code ec;
    walkElements(ctx, root, w, {fs::weakly_canonical(path, ec).string()});
    // The integrator is known now (the caller's, else the file's): shapes read the emitters it reads.
    if (const IntegratorInfo *known = findIntegrator(integrator.empty() ? scene.integrator.type : integrator)) {
        w.deferred.known = true;
        w.deferred.reads = known->use.emitters;
        w.deferred.readsTextures = known->use.readsAnyBsdf;
    }
    loadSetAside(ctx, w);
    scene.bsdfs = w.defs.list;
    Deferred &deferred = w.deferred;
    std::vector<std::string> skipped;
    if (!w.hasSensor) ctx.fail(root, "the scene has no <sensor type=\"perspective\"> or <sensor type=\"orthographic\">");
    if (scene.meshes.empty() && scene.spheres.empty() && scene.disks.empty() && scene.cylinders.empty())
        ctx.fail(root, "the scene has no <shape>");

    // What the chosen integrator uses, as it declared: refuse what would change its answer, skip the rest.
    if (!integrator.empty() && integrator != scene.integrator.type) scene.integrator = {integrator, {}};
    const std::string &chosen = scene.integrator.type;
    const IntegratorInfo *info = findIntegrator(chosen);
    if (!info) {
        // No or an unknown integrator: render() names that error; a bsdf we cannot model is one too.
        for (const auto &[node, what] : deferred.unmodelledBsdfs)
            ctx.fail(node, "unsupported bsdf type \"" + typeOf(ctx, node) + "\"");
        return scene;
    }
    if (info->use.needsPointLight && scene.pointLights.empty())
        ctx.fail(root, "the scene has no point light, the only emitter the " + chosen + " integrator uses");
    // An area emitter kept aside is one the integrator does not read (those it reads are on their shapes).
    for (const auto &[node, what] : deferred.areaEmitters) skipped.push_back(what);
    judgeOtherEmitters(ctx, deferred, chosen, scene, skipped);
    for (const auto &[node, what] : deferred.media) skipped.push_back(what);
    for (const auto &[node, what] : deferred.unreferencedBsdfs) skipped.push_back(what);
    for (const auto &[node, what] : deferred.textures) skipped.push_back(what);
    for (const auto &unread : deferred.unreadReflectances) {
        if (info->use.readsReflectance && unread.diffuse)
            ctx.fail(unread.node, "the " + chosen + " integrator reads the reflectance, given here as " + unread.given +
                                      "; this renderer reads an <rgb>, a <float> or a <spectrum> given by its values");
        if (info->use.readsReflectance)
            ctx.fail(unread.node, "the " + chosen + " integrator reads this material, given here with " + unread.given +
                                      "; this renderer reads its parameters as constants");
        skipped.push_back(unread.what);
    }
    for (const auto &[node, what] : deferred.unmodelledBsdfs) {
        if (info->use.readsReflectance)
            ctx.fail(node, "unsupported bsdf type \"" + typeOf(ctx, node) + "\": the " + chosen + " integrator needs "
                           "diffuse" + std::string(info->use.readsAnyBsdf ? ", conductor, dielectric, plastic or "
                                                                            "their rough kinds" : ""));
        skipped.push_back(what);
    }
    for (const auto &[node, what] : deferred.texturedBsdfs) {
        if (info->use.readsReflectance && !info->use.readsAnyBsdf)
            ctx.fail(node, "the " + chosen + " integrator reads one reflectance per surface, not a texture: direct "
                           "and path read it");
        if (!info->use.readsReflectance) skipped.push_back(what);
    }
    for (const auto &[node, what] : deferred.nonDiffuseBsdfs) {
        if (info->use.readsReflectance && !info->use.readsAnyBsdf)
            ctx.fail(node, "the " + chosen + " integrator reads diffuse surfaces only, not <bsdf type=\"" +
                               typeOf(ctx, node) + "\">: direct and path read it");
        if (!info->use.readsReflectance) skipped.push_back(what);
    }
    if (!skipped.empty()) {
        std::string note = "note: " + path + ": skipped, not used by the " + chosen + " integrator:";
        for (size_t i = 0; i < skipped.size(); ++i) note += (i ? "; " : " ") + skipped[i];
        std::cerr << note << std::endl;
    }
    return scene;
}

}  // namespace mcval
