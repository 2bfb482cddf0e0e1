#include "scene_bsdfs.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <optional>
#include <utility>

#include "bsdfs/conductor.h"
#include "bsdfs/dielectric.h"
#include "bsdfs/plastic.h"
#include "bsdfs/roughconductor.h"
#include "bsdfs/roughdielectric.h"
#include "bsdfs/roughplastic.h"

namespace mcval {

namespace {

/// Mitsuba's named indices of refraction (include/mitsuba/render/ior.h), looked up without case.
constexpr std::pair<const char *, float> kIors[] = {
    {"vacuum", 1.0f},           {"helium", 1.000036f},       {"hydrogen", 1.000132f},
    {"air", 1.000277f},         {"carbon dioxide", 1.00045f}, {"water", 1.3330f},
    {"acetone", 1.36f},         {"ethanol", 1.361f},          {"carbon tetrachloride", 1.461f},
    {"glycerol", 1.4729f},      {"benzene", 1.501f},          {"silicone oil", 1.52045f},
    {"bromine", 1.661f},        {"water ice", 1.31f},         {"fused quartz", 1.458f},
    {"pyrex", 1.470f},          {"acrylic glass", 1.49f},     {"polypropylene", 1.49f},
    {"bk7", 1.5046f},           {"sodium chloride", 1.544f},  {"amber", 1.55f},
    {"pet", 1.5750f},           {"diamond", 2.419f},
};

/// One <bsdf>'s properties, read as constants; the first form it cannot read is kept in `unread`.
class BsdfReader {
public:
    BsdfReader(const XmlContext &ctx, const pugi::xml_node &node, std::string &unread)
        : m_ctx(ctx), m_props(ctx, node), m_unread(unread) {
        // A texture or a reference to one stands for a property that then varies over the surface.
        for (const auto &child : m_props.objects()) {
            const std::string texture = textureGiven(ctx, child);
            if (texture.empty())
                ctx.fail(child, "unexpected element inside <bsdf type=\"" + ctx.attr(node, "type") + "\">");
            note(texture + (child.attribute("name") ? " (" + ctx.attr(child, "name") + ")" : "") + ctx.at(child));
        }
    }

    bool complete() const { return m_unread.empty(); }
    XmlProps &props() { return m_props; }

    /// A colour (an <rgb>, a <float>, a <spectrum>) in [lo, hi].
    Color color(const std::string &name, const Color &def, float lo, float hi) {
        if (unreadSpectrum(name, false)) return def;
        const Color c = m_props.getColor(name, def);
        m_props.requireRange(name, c, lo, hi);
        return c;
    }

    /// One value for every channel: a colour whose channels differ, or a per-wavelength spectrum (which Mitsuba's
    /// RGB variants would clamp to [0, 1] as a reflectance), is noted unread.
    float scalar(const std::string &name, float def, float lo, float hi) {
        if (unreadSpectrum(name, true)) return def;
        const Color c = color(name, Color(def, def, def), lo, hi);
        if (c.x != c.y || c.y != c.z) note(name + " that differs by channel" + m_ctx.at(m_props.node(name)));
        return c.x;
    }

    /// An index of refraction: a number or one of Mitsuba's names.
    float ior(const std::string &name, const char *def) {
        const pugi::xml_node node = m_props.node(name);
        if (node && std::string(node.name()) != "string") return scalar(name, 1.f, 1e-4f, 1e4f);
        std::string text = m_props.getString(name, def);
        std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
        for (const auto &[known, value] : kIors)
            if (text == known) return value;
        std::string names;
        for (const auto &[known, value] : kIors) names += std::string(names.empty() ? "" : ", ") + known;
        m_props.failAt(name, "unknown index of refraction \"" + text + "\": give a number or one of " + names);
    }

    /// The interior and exterior indices, which Mitsuba requires to differ.
    std::pair<float, float> iors(const char *intDefault) {
        const float in = ior("int_ior", intDefault), out = ior("ext_ior", "air");
        if (in == out) m_props.failAt("int_ior", "the interior and exterior indices of refraction must differ");
        return {in, out};
    }

    /// The microfacet distribution: `distribution`, `alpha` (or equal `alpha_u` and `alpha_v` where
    /// `anisotropic` names are read) and `sample_visible`.
    MicrofacetDistribution distribution(bool anisotropicNames) {
        const std::string type = m_props.getString("distribution", "beckmann");
        if (type != "beckmann" && type != "ggx")
            m_props.failAt("distribution", "distribution must be beckmann or ggx, not \"" + type + "\"");
        float alpha = 0.1f;
        if (anisotropicNames && (m_props.has("alpha_u") || m_props.has("alpha_v"))) {
            if (m_props.has("alpha")) m_props.failAt("alpha", "give alpha or alpha_u and alpha_v, not both");
            const float u = scalar("alpha_u", 0.1f, 1e-4f, 1e4f), v = scalar("alpha_v", 0.1f, 1e-4f, 1e4f);
            if (u != v) note("anisotropic roughness (alpha_u " + num(u) + ", alpha_v " + num(v) + ")");
            alpha = u;
        } else {
            alpha = scalar("alpha", 0.1f, 1e-4f, 1e4f);
        }
        const bool visible = m_props.getBool("sample_visible", true);
        return MicrofacetDistribution(type == "ggx" ? MicrofacetDistribution::Type::GGX
                                                    : MicrofacetDistribution::Type::Beckmann,
                                      alpha, visible);
    }

    /// A conductor's eta and k: given as values, or by `material` "none" (a perfect mirror, Mitsuba's default).
    std::pair<float, float> conductor() {
        const std::string material = m_props.getString("material", "none");
        if (material != "none") {
            if (m_props.has("eta") || m_props.has("k"))
                m_props.failAt("material", "give a material or eta and k, not both (as Mitsuba)");
            note("the named conductor \"" + material + "\" (its per-wavelength eta and k)" +
                 m_ctx.at(m_props.node("material")));
            return {0.f, 1.f};
        }
        return {scalar("eta", 0.f, 0.f, 1e4f), scalar("k", 1.f, 0.f, 1e4f)};
    }

    /// A specular reflectance (or transmittance) this renderer models only at its default 1.
    void unitOnly(const std::string &name) {
        if (!m_props.has(name)) return;
        const Color c = color(name, Color(1.f, 1.f, 1.f), 0.f, 1.f);
        if (c.x != 1.f || c.y != 1.f || c.z != 1.f) note(name + " other than 1" + m_ctx.at(m_props.node(name)));
    }

private:
    /// Whether property `name` is a <spectrum> read from a file or, with `valuesToo`, one given per wavelength:
    /// then it is noted unread.
    bool unreadSpectrum(const std::string &name, bool valuesToo) {
        const pugi::xml_node node = m_props.node(name);
        if (!node || std::string(node.name()) != "spectrum") return false;
        const bool file = node.attribute("filename");
        if (!file && !(valuesToo && isPerWavelength(node))) return false;
        m_props.ignore(name);
        note(std::string(file ? "a <spectrum> read from a file" : "a per-wavelength <spectrum>") + " (" + name + ")" +
             m_ctx.at(node));
        return true;
    }
    void note(const std::string &what) {
        if (m_unread.empty()) m_unread = what;
    }
    static std::string num(float v) {
        std::string s = std::to_string(v);
        return s.substr(0, s.find_last_not_of('0') + 1);
    }

    const XmlContext &m_ctx;
    XmlProps m_props;
    std::string &m_unread;
};

Material readConductor(BsdfReader &r, bool rough) {
    std::optional<MicrofacetDistribution> distribution;
    if (rough) distribution = r.distribution(true);
    const auto [eta, k] = r.conductor();
    const Color specular = r.color("specular_reflectance", Color(1.f, 1.f, 1.f), 0.f, 1.f);
    r.props().finish(rough ? "distribution, alpha (or alpha_u, alpha_v), sample_visible, material, eta, k, "
                             "specular_reflectance"
                           : "material, eta, k, specular_reflectance");
    if (!r.complete()) return nullptr;
    if (rough) return std::make_shared<RoughConductorBsdf>(*distribution, eta, k, specular);
    return std::make_shared<ConductorBsdf>(eta, k, specular);
}

Material readDielectric(BsdfReader &r, bool rough) {
    std::optional<MicrofacetDistribution> distribution;
    if (rough) distribution = r.distribution(true);
    const auto [in, out] = r.iors("bk7");
    r.unitOnly("specular_reflectance");
    r.unitOnly("specular_transmittance");
    r.props().finish(std::string(rough ? "distribution, alpha (or alpha_u, alpha_v), sample_visible, " : "") +
                     "int_ior, ext_ior, specular_reflectance, specular_transmittance");
    if (!r.complete()) return nullptr;
    if (rough) return std::make_shared<RoughDielectricBsdf>(*distribution, in, out);
    return std::make_shared<DielectricBsdf>(in, out);
}

Material readPlastic(BsdfReader &r, bool rough) {
    std::optional<MicrofacetDistribution> distribution;
    if (rough) distribution = r.distribution(false);
    const auto [in, out] = r.iors("polypropylene");
    const Color diffuse = r.color("diffuse_reflectance", Color(0.5f, 0.5f, 0.5f), 0.f, 1.f);
    r.unitOnly("specular_reflectance");
    const bool nonlinear = r.props().getBool("nonlinear", false);
    r.props().finish(std::string(rough ? "distribution, alpha, sample_visible, " : "") +
                     "int_ior, ext_ior, diffuse_reflectance, specular_reflectance, nonlinear");
    if (!r.complete()) return nullptr;
    if (rough) return std::make_shared<RoughPlasticBsdf>(*distribution, in, out, diffuse, nonlinear);
    return std::make_shared<PlasticBsdf>(in, out, diffuse, nonlinear);
}

}  // namespace

std::string textureGiven(const XmlContext &ctx, const pugi::xml_node &child) {
    const std::string tag = child.name();
    if (tag == "texture") return "a " + ctx.attr(child, "type") + " texture";
    if (tag == "ref") return "a reference to \"" + ctx.attr(child, "id") + "\" (a texture)";
    return "";
}

bool isScatteringBsdf(const std::string &type) {
    return type == "conductor" || type == "roughconductor" || type == "dielectric" || type == "roughdielectric" ||
           type == "plastic" || type == "roughplastic";
}

Material readScatteringBsdf(const XmlContext &ctx, const pugi::xml_node &node, std::string &unread) {
    const std::string type = ctx.attr(node, "type");
    BsdfReader reader(ctx, node, unread);
    const bool rough = type.rfind("rough", 0) == 0;
    const std::string base = rough ? type.substr(5) : type;
    if (base == "conductor") return readConductor(reader, rough);
    if (base == "dielectric") return readDielectric(reader, rough);
    return readPlastic(reader, rough);
}

}  // namespace mcval
