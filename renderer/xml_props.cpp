#include "xml_props.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "error.h"

namespace mcval {

namespace {
const std::set<std::string> kPropertyTags = {"float", "integer", "boolean", "string", "rgb",
                                             "point", "vector", "transform", "spectrum"};

std::vector<std::string> splitNumbers(const std::string &text) {
    std::string s = text;
    std::replace(s.begin(), s.end(), ',', ' ');
    std::istringstream in(s);
    std::vector<std::string> out;
    for (std::string tok; in >> tok;) out.push_back(tok);
    return out;
}
}  // namespace

namespace {
/// The included file `node` was read from, or null for the scene file itself.
const XmlContext::Included *includedOf(const XmlContext &ctx, const pugi::xml_node &node) {
    const pugi::xml_node document = node.root();
    for (const auto &inc : ctx.included)
        if (inc.doc == document) return &inc;
    return nullptr;
}
}  // namespace

int XmlContext::line(const pugi::xml_node &node) const {
    const ptrdiff_t offset = node.offset_debug();
    if (offset < 0) return 0;
    const Included *inc = includedOf(*this, node);
    const std::string &source = inc ? inc->text : text;
    return 1 + static_cast<int>(std::count(source.begin(), source.begin() + std::min<size_t>(offset, source.size()),
                                           '\n'));
}

const std::string &XmlContext::fileOf(const pugi::xml_node &node) const {
    const Included *inc = includedOf(*this, node);
    return inc ? inc->file : file;
}

std::string XmlContext::resolve(const std::string &name) const {
    const std::filesystem::path given(name);
    if (given.is_absolute() || folders.empty()) return name;
    std::error_code ec;
    for (const std::string &folder : folders) {
        const std::filesystem::path candidate = std::filesystem::path(folder) / given;
        if (std::filesystem::exists(candidate, ec)) return candidate.string();
    }
    return (std::filesystem::path(folders.back()) / given).string();
}

void XmlContext::fail(const pugi::xml_node &node, const std::string &message) const {
    throw SceneError(fileOf(node), line(node), "<" + std::string(node.name()) + ">: " + message);
}

std::string XmlContext::attr(const pugi::xml_node &node, const char *name) const {
    std::string value = node.attribute(name).value();
    for (size_t pos = value.find('$'); pos != std::string::npos; pos = value.find('$', pos)) {
        size_t end = pos + 1;
        while (end < value.size() && (std::isalnum(static_cast<unsigned char>(value[end])) || value[end] == '_')) ++end;
        const std::string key = value.substr(pos + 1, end - pos - 1);
        const auto it = params.find(key);
        if (it == params.end())
            fail(node, "parameter $" + key + " has no <default> and was not given (e.g. -D " + key + "=...)");
        value.replace(pos, end - pos, it->second);
        pos += it->second.size();
    }
    return value;
}

XmlProps::XmlProps(const XmlContext &ctx, const pugi::xml_node &element) : m_ctx(ctx), m_element(element) {
    for (pugi::xml_node child : element.children()) {
        if (child.type() != pugi::node_element) continue;
        if (!kPropertyTags.count(child.name())) {
            m_objects.push_back(child);
            continue;
        }
        const std::string name = child.attribute("name").value();
        if (name.empty()) ctx.fail(child, "property without a name attribute");
        if (m_props.count(name)) ctx.fail(child, "property \"" + name + "\" given twice");
        m_props[name] = child;
    }
}

pugi::xml_node XmlProps::find(const std::string &name, const char *tag) {
    const auto it = m_props.find(name);
    if (it == m_props.end()) return {};
    m_used.insert(name);
    if (std::string(it->second.name()) != tag)
        m_ctx.fail(it->second, "property \"" + name + "\" must be a <" + tag + ">");
    return it->second;
}

float XmlProps::parseFloat(const pugi::xml_node &node, const std::string &text) const {
    errno = 0;
    char *end = nullptr;
    const float v = std::strtof(text.c_str(), &end);
    if (text.empty() || *end != '\0') m_ctx.fail(node, "expected a number, got \"" + text + "\"");
    // strtof reads "nan", "inf" and "infinity": none of them is a scene quantity.
    if (!std::isfinite(v) || (errno == ERANGE && v != 0.f && std::abs(v) >= 1.f))
        m_ctx.fail(node, "expected a finite number, got \"" + text + "\"");
    if (errno == ERANGE) return 0.f;  // below float precision: a denormal or zero
    return v;
}

Vec3f XmlProps::parseTriple(const pugi::xml_node &node, const std::string &text) const {
    const auto parts = splitNumbers(text);
    if (parts.size() == 1) {
        const float v = parseFloat(node, parts[0]);
        return {v, v, v};
    }
    if (parts.size() != 3) m_ctx.fail(node, "expected three numbers \"x, y, z\", got \"" + text + "\"");
    return {parseFloat(node, parts[0]), parseFloat(node, parts[1]), parseFloat(node, parts[2])};
}

float XmlProps::getFloat(const std::string &name, float def) {
    const auto node = find(name, "float");
    return node ? parseFloat(node, m_ctx.attr(node, "value")) : def;
}

float XmlProps::getFloatRequired(const std::string &name) {
    if (!m_props.count(name)) m_ctx.fail(m_element, "missing <float name=\"" + name + "\" value=\"...\"/>");
    return getFloat(name, 0.f);
}

int XmlProps::getInt(const std::string &name, int def) {
    const auto node = find(name, "integer");
    if (!node) return def;
    const std::string text = m_ctx.attr(node, "value");
    errno = 0;
    char *end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno == ERANGE || v < -2147483647L || v > 2147483647L)
        m_ctx.fail(node, "expected an integer, got \"" + text + "\"");
    return static_cast<int>(v);
}

bool XmlProps::getBool(const std::string &name, bool def) {
    const auto node = find(name, "boolean");
    if (!node) return def;
    const std::string text = m_ctx.attr(node, "value");
    if (text == "true") return true;
    if (text == "false") return false;
    m_ctx.fail(node, "expected true or false, got \"" + text + "\"");
}

std::string XmlProps::getString(const std::string &name, const std::string &def) {
    const auto node = find(name, "string");
    return node ? m_ctx.attr(node, "value") : def;
}

std::string XmlProps::getStringRequired(const std::string &name) {
    if (!m_props.count(name)) m_ctx.fail(m_element, "missing <string name=\"" + name + "\" value=\"...\"/>");
    return getString(name, "");
}

bool isPerWavelength(const pugi::xml_node &spectrum) {
    return spectrum.attribute("filename") ||
           std::string(spectrum.attribute("value").value()).find(':') != std::string::npos;
}

Vec3f XmlProps::getColor(const std::string &name, const Vec3f &def) {
    const auto it = m_props.find(name);
    if (it == m_props.end()) return def;
    m_used.insert(name);
    const std::string tag = it->second.name();
    if (tag == "float") {
        const float v = parseFloat(it->second, m_ctx.attr(it->second, "value"));
        return {v, v, v};
    }
    if (tag == "spectrum") {
        // A constant spectrum is that value in RGB too; per-wavelength values become RGB by Mitsuba's own
        // colour matching, which this renderer does not model.
        const std::string value = m_ctx.attr(it->second, "value");
        if (isPerWavelength(it->second))
            m_ctx.fail(it->second, "property \"" + name + "\": a <spectrum> given per wavelength becomes RGB by "
                                   "Mitsuba's colour matching, which this renderer does not model: give an <rgb>");
        const float v = parseFloat(it->second, value);
        return {v, v, v};
    }
    if (tag != "rgb") m_ctx.fail(it->second, "property \"" + name + "\" must be an <rgb>, a <spectrum> or a <float>");
    return parseTriple(it->second, m_ctx.attr(it->second, "value"));
}

Vec3f XmlProps::getPoint(const std::string &name, const Vec3f &def) {
    const auto node = find(name, "point");
    if (!node) return def;
    if (node.attribute("value")) return parseTriple(node, m_ctx.attr(node, "value"));
    const auto coord = [&](const char *a) {
        return node.attribute(a) ? parseFloat(node, m_ctx.attr(node, a)) : 0.f;
    };
    return {coord("x"), coord("y"), coord("z")};
}

Transform XmlProps::getTransform(const std::string &name) {
    const auto node = find(name, "transform");
    return node ? parseTransform(node) : Transform();
}

Transform XmlProps::parseTransform(const pugi::xml_node &node) const {
    Transform result;
    for (pugi::xml_node step : node.children()) {
        if (step.type() != pugi::node_element) continue;
        try {
            result = parseTransformStep(step) * result;  // later steps apply after earlier ones
        } catch (const std::domain_error &e) {
            m_ctx.fail(step, e.what());  // singular or overflowing: Transform knows no file or line
        }
    }
    return result;
}

Transform XmlProps::parseTransformStep(const pugi::xml_node &step) const {
    const std::string tag = step.name();
    const auto triple = [&](float def) {
        if (step.attribute("value")) return parseTriple(step, m_ctx.attr(step, "value"));
        const auto c = [&](const char *a) { return step.attribute(a) ? parseFloat(step, m_ctx.attr(step, a)) : def; };
        return Vec3f(c("x"), c("y"), c("z"));
    };
    if (tag == "translate") return Transform::translate(triple(0.f));
    if (tag == "scale") return Transform::scale(triple(1.f));
    if (tag == "rotate") {
        if (!step.attribute("angle")) m_ctx.fail(step, "missing angle=\"degrees\"");
        const Vec3f axis = triple(0.f);
        if (squaredNorm(axis) == 0.f) m_ctx.fail(step, "rotation axis is zero: give x, y or z");
        // Mitsuba 3 uses the axis as given: a non-unit one makes its rotation a shear, ours would not.
        const double length = std::sqrt(double(axis.x) * axis.x + double(axis.y) * axis.y + double(axis.z) * axis.z);
        if (!(std::abs(length - 1.0) <= 1e-5)) {
            std::ostringstream msg;
            msg << "rotate axis (" << axis.x << ", " << axis.y << ", " << axis.z << ") has length "
                << std::setprecision(4) << length
                << ", not 1: Mitsuba 3 would shear with it (it does not normalise); give a unit axis";
            m_ctx.fail(step, msg.str());
        }
        return Transform::rotate(axis, parseFloat(step, m_ctx.attr(step, "angle")));
    }
    if (tag == "matrix") {
        const auto parts = splitNumbers(m_ctx.attr(step, "value"));
        if (parts.size() != 16) m_ctx.fail(step, "expected 16 numbers in value");
        float a[16];
        for (int i = 0; i < 16; ++i) a[i] = parseFloat(step, parts[i]);
        return Transform(a);
    }
    if (tag == "lookat") {
        const auto vec = [&](const char *a, bool required) {
            if (!step.attribute(a)) {
                if (required) m_ctx.fail(step, std::string("missing ") + a + "=\"x, y, z\"");
                return Vec3f(0.f, 1.f, 0.f);
            }
            return parseTriple(step, m_ctx.attr(step, a));
        };
        const Vec3f origin = vec("origin", true), target = vec("target", true), up = vec("up", false);
        const Vec3f dir = target - origin;
        if (!std::isfinite(squaredNorm(dir))) m_ctx.fail(step, "origin and target are too far apart for float32");
        if (!(squaredNorm(dir) > 0.f)) m_ctx.fail(step, "origin and target coincide");
        if (!(squaredNorm(cross(normalize(up), normalize(dir))) > 1e-12f))
            m_ctx.fail(step, "up is zero or parallel to the view direction");
        return Transform::lookAt(origin, target, up);
    }
    m_ctx.fail(step, "unsupported transform step: expected translate, scale, rotate, matrix or lookat");
}

void XmlProps::requireRange(const std::string &name, const Vec3f &value, float lo, float hi) const {
    for (int i = 0; i < 3; ++i) {
        if (value[i] >= lo && value[i] <= hi) continue;
        std::ostringstream msg;
        msg << name << " must lie in [" << lo << ", " << hi << "], got " << value[i];
        failAt(name, msg.str());
    }
}

void XmlProps::requireRange(const std::string &name, int value, int lo, int hi) const {
    if (value < lo || value > hi)
        failAt(name, name + " must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
                         std::to_string(value));
}

void XmlProps::failAt(const std::string &name, const std::string &message) const {
    const auto it = m_props.find(name);
    m_ctx.fail(it != m_props.end() ? it->second : m_element, message);
}

void XmlProps::finish(const std::string &expected) const {
    for (const auto &[name, node] : m_props)
        if (!m_used.count(name))
            m_ctx.fail(node, "unsupported property \"" + name + "\" of <" + m_element.name() + " type=\"" +
                                 m_element.attribute("type").value() + "\">: expected " + expected);
}

}  // namespace mcval
