#include "bsdf_loader.h"

#include <limits>
#include <string>
#include <vector>

#include "bsdfs/diffuse.h"
#include "bsdfs/mask.h"
#include "bsdfs/textured_diffuse.h"
#include "bsdfs/twosided.h"
#include "scene_bsdfs.h"
#include "textures/texture_loader.h"

namespace mcval {

namespace {

/// The <texture> a diffuse reflectance is given as: the child itself, or the top-level one a <ref> names; an
/// empty node for another element or an unknown id.
pugi::xml_node textureNode(const XmlContext &ctx, const pugi::xml_node &child, const Deferred &deferred) {
    if (std::string(child.name()) == "texture") return child;
    if (std::string(child.name()) != "ref") return {};
    const std::string id = ctx.attr(child, "id");
    for (const auto &[node, what] : deferred.textures)
        if (node.attribute("id") && ctx.attr(node, "id") == id) return node;
    return {};
}

/// A texture the diffuse reflectance is given as, where the integrator reads textures (or is not known yet):
/// the textured surface, or nullptr where the texture is of a type this renderer does not read.
Material readTexturedDiffuse(const XmlContext &ctx, const pugi::xml_node &node, const XmlProps &props,
                             const pugi::xml_node &child, Deferred &deferred) {
    if (deferred.known && !deferred.readsTextures) return nullptr;
    const pugi::xml_node texture = textureNode(ctx, child, deferred);
    if (!texture || !isModelledTexture(ctx.attr(texture, "type"))) return nullptr;
    if (ctx.propertyName(child) != "reflectance")
        ctx.fail(child, "unexpected texture \"" + ctx.propertyName(child) + "\" inside <bsdf type=\"diffuse\">: "
                        "expected reflectance");
    props.finish("reflectance");
    deferred.texturedBsdfs.emplace_back(node, "<bsdf type=\"diffuse\">" + ctx.at(node) + " (reflectance: a " +
                                                  ctx.attr(texture, "type") + " texture)");
    return std::make_shared<TexturedDiffuseBsdf>(loadTexture(ctx, texture, 1.f));
}

/// The diffuse bsdf's reflectance: a value, or a bitmap or checkerboard texture for the integrators that read
/// them. One we cannot read (another texture, a per-wavelength spectrum from a file) is deferred: whether it may
/// go unread is decided when the integrator is known.
Material readDiffuse(const XmlContext &ctx, const pugi::xml_node &node, Deferred &deferred) {
    XmlProps props(ctx, node);
    std::string unread;
    if (props.objects().size() == 1)
        if (Material textured = readTexturedDiffuse(ctx, node, props, props.objects()[0], deferred)) return textured;
    for (const auto &child : props.objects())
        if (const std::string texture = textureGiven(ctx, child); !texture.empty()) unread = texture + ctx.at(child);
    const pugi::xml_node given = props.node("reflectance");
    if (given && std::string(given.name()) == "spectrum" && given.attribute("filename"))
        unread = "a <spectrum> read from a file" + ctx.at(given);
    if (!unread.empty()) {
        deferred.unreadReflectances.push_back(
            {node, "<bsdf type=\"diffuse\">" + ctx.at(node) + " (reflectance: " + unread + ")", unread, true});
        return defaultBsdf();
    }
    const Color rho = props.getColor("reflectance", {0.5f, 0.5f, 0.5f});
    props.requireRange("reflectance", rho, 0.f, 1.f);
    props.finish("reflectance");
    if (!props.objects().empty()) ctx.fail(props.objects()[0], "unexpected element inside <bsdf>");
    return std::make_shared<DiffuseBsdf>(rho);
}

/// Mitsuba's twosided: its first bsdf on the front, its second (or the first again) on the back, each side
/// seen as that bsdf's front (a twosided inside one adds nothing).
Material readTwoSided(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred,
                      int depth) {
    XmlProps props(ctx, node);
    props.ignore("allow_transmission");  // diffuse sides transmit nothing
    props.finish("allow_transmission (and one or two nested bsdfs)");
    std::vector<Material> sides;
    for (const auto &child : props.objects()) {
        const std::string tag = child.name();
        if (tag != "bsdf" && tag != "ref")
            ctx.fail(child, "unexpected element inside <bsdf type=\"twosided\">: expected <bsdf> or <ref>");
        if (sides.size() == 2) ctx.fail(child, "a twosided bsdf holds at most two bsdfs (front, back)");
        // Mitsuba's twosided mirrors directions to the front side, which a transmitted one would leave.
        const auto named = tag == "ref" ? defs.bsdfNodes.find(ctx.attr(child, "id")) : defs.bsdfNodes.end();
        const std::string sideType = ctx.attr(named != defs.bsdfNodes.end() ? named->second : child, "type");
        if (sideType == "dielectric" || sideType == "roughdielectric" || sideType == "thindielectric")
            ctx.fail(child, "a twosided bsdf holds only bsdfs that transmit no light (as Mitsuba), not a " + sideType);
        sides.push_back(tag == "bsdf" ? loadBsdf(ctx, child, defs, deferred, depth + 1)
                                      : resolveBsdfRef(ctx, child, defs, deferred, depth + 1));
        if (dynamic_cast<const TexturedBsdf *>(sides.back().get()))
            ctx.fail(child, "a twosided bsdf around a textured diffuse or a mask is not modelled");
    }
    if (sides.empty()) ctx.fail(node, "a twosided bsdf needs a nested <bsdf> or <ref> (its one-sided material)");
    return std::make_shared<TwoSidedBsdf>(sides[0], sides.back());
}

/// Mitsuba's mask: an opacity (a value in [0, 1], or a bitmap or checkerboard texture, 0.5 by default) and one
/// nested bsdf, read where the integrator reads any BSDF. Elsewhere it is left unread: simple refuses it (one albedo
/// per surface) and ao and normals read no material.
Material readMask(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred,
                  int depth) {
    const std::string what = "<bsdf type=\"mask\">" + ctx.at(node);
    deferred.nonDiffuseBsdfs.emplace_back(node, what);
    if (deferred.known && !deferred.readsTextures) return defaultBsdf();
    XmlProps props(ctx, node);
    std::shared_ptr<const Texture> opacity;
    Material nested;
    for (const auto &child : props.objects()) {
        const std::string tag = child.name();
        if (ctx.propertyName(child) == "opacity" && (tag == "texture" || tag == "ref")) {
            const pugi::xml_node texture = textureNode(ctx, child, deferred);
            if (!texture || !isModelledTexture(ctx.attr(texture, "type")))
                ctx.fail(child, "a mask's opacity is read as a value, a bitmap or a checkerboard texture");
            opacity = loadTexture(ctx, texture, std::numeric_limits<float>::max());
        } else if (tag == "bsdf" || tag == "ref") {
            if (nested) ctx.fail(child, "a mask holds one bsdf");
            nested = tag == "bsdf" ? loadBsdf(ctx, child, defs, deferred, depth + 1)
                                   : resolveBsdfRef(ctx, child, defs, deferred, depth + 1);
            if (dynamic_cast<const MaskBsdf *>(nested.get())) ctx.fail(child, "a mask inside a mask is not modelled");
        } else {
            ctx.fail(child, "unexpected element inside <bsdf type=\"mask\">: expected <bsdf>, <ref> or the opacity's "
                            "<texture>");
        }
    }
    if (!nested) ctx.fail(node, "a mask needs a nested <bsdf> or <ref> (the material where it is opaque)");
    const float constant = opacity ? 1.f : props.getFloat("opacity", 0.5f);
    props.requireRange("opacity", constant, 0.f, 1.f);
    props.finish("opacity (and one nested bsdf)");
    return std::make_shared<MaskBsdf>(opacity, constant, nested);
}

Material readBsdf(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred,
                  int depth) {
    const std::string type = ctx.attr(node, "type");
    // Every integrator of ours reads the shading normal, which these perturb (Mitsuba's sh_normal shows it).
    if (type == "bumpmap" || type == "normalmap")
        ctx.fail(node, "a <bsdf type=\"" + type + "\"> perturbs the shading normal, which every integrator here "
                       "reads and this renderer does not model");
    if (type == "twosided") return readTwoSided(ctx, node, defs, deferred, depth);
    if (type == "diffuse") return readDiffuse(ctx, node, deferred);
    if (type == "mask") return readMask(ctx, node, defs, deferred, depth);
    if (isScatteringBsdf(type)) {
        std::string unread;
        const Material material = readScatteringBsdf(ctx, node, unread);
        const std::string what = "<bsdf type=\"" + type + "\">" + ctx.at(node);
        if (!material) {
            deferred.unreadReflectances.push_back({node, what + " (" + unread + ")", unread, false});
            return defaultBsdf();
        }
        // Read by the integrators that read any BSDF; one that reads Lambertian albedos refuses it.
        deferred.nonDiffuseBsdfs.emplace_back(node, what);
        return material;
    }
    // Only integrators that read no material can ignore it; which is decided when the integrator is known.
    deferred.unmodelledBsdfs.emplace_back(node, "<bsdf type=\"" + type + "\">" + ctx.at(node));
    return defaultBsdf();
}

}  // namespace

void registerBsdfs(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs) {
    // Iterative: a file may nest elements thousands deep.
    std::vector<pugi::xml_node> stack{node};
    while (!stack.empty()) {
        const pugi::xml_node n = stack.back();
        stack.pop_back();
        if (std::string(n.name()) == "bsdf" && n.attribute("id")) {
            const std::string id = ctx.attr(n, "id");
            const auto [it, added] = defs.bsdfNodes.emplace(id, n);
            if (!added)
                ctx.fail(n, "the id \"" + id + "\" is already defined (in " + ctx.fileOf(it->second) + ctx.at(it->second) +
                                ")");
        }
        for (pugi::xml_node child = n.last_child(); child; child = child.previous_sibling())
            if (child.type() == pugi::node_element) stack.push_back(child);
    }
}

Material loadBsdf(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred, int depth) {
    if (depth > kMaxBsdfDepth)
        ctx.fail(node, "bsdfs nested (or referenced through one another) more than " + std::to_string(kMaxBsdfDepth) +
                           " deep");
    const std::string id = node.attribute("id") ? ctx.attr(node, "id") : "";
    if (id.empty()) return readBsdf(ctx, node, defs, deferred, depth);
    if (const auto it = defs.bsdfs.find(id); it != defs.bsdfs.end()) return it->second;
    if (!defs.reading.insert(id).second) ctx.fail(node, "the bsdf \"" + id + "\" refers to itself");
    const Material material = readBsdf(ctx, node, defs, deferred, depth);
    defs.reading.erase(id);
    return defs.bsdfs[id] = material;
}

Material resolveBsdfRef(const XmlContext &ctx, const pugi::xml_node &ref, Definitions &defs, Deferred &deferred,
                        int depth) {
    const std::string id = ctx.attr(ref, "id");
    if (defs.groups.count(id))
        ctx.fail(ref, "<ref id=\"" + id + "\"> names a shapegroup: only a <shape type=\"instance\"> may refer to one");
    const auto it = defs.bsdfNodes.find(id);
    if (it == defs.bsdfNodes.end()) ctx.fail(ref, "no <bsdf id=\"" + id + "\"> in the file");
    if (defs.reading.count(id)) ctx.fail(ref, "the bsdf \"" + id + "\" refers to itself");
    return loadBsdf(ctx, it->second, defs, deferred, depth);
}

}  // namespace mcval
