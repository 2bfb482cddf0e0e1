#include "xml_props.h"

#include <algorithm>
#include <cctype>
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
}  // namespace

std::vector<std::string> splitNumbers(const std::string &text) {
    std::string s = text;
    std::replace(s.begin(), s.end(), ',', ' ');
    std::istringstream in(s);
    std::vector<std::string> out;
    for (std::string tok; in >> tok;) out.push_back(tok);
    return out;
}

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

std::string XmlContext::resolve(const std::string &name, const std::vector<std::string> &folders) {
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

namespace {
/// Whether the file `node` was read from declares a version before 2.0.0 ("0.5.0", "0.6.0").
bool isBeforeVersion2(const pugi::xml_node &node) {
    pugi::xml_node root = node.root().first_child();
    while (root && root.type() != pugi::node_element) root = root.next_sibling();
    const std::string version = root.attribute("version").value();
    return !version.empty() && std::isdigit(static_cast<unsigned char>(version[0])) && std::atoi(version.c_str()) < 2;
}

/// Mitsuba's camel_to_underscore_case: "toWorld" -> "to_world", "fovAxis" -> "fov_axis", "sRGB" -> "s_rgb".
std::string snakeCase(const std::string &name) {
    std::string out;
    for (size_t i = 0; i < name.size(); ++i) {
        const auto c = static_cast<unsigned char>(name[i]);
        if (i > 0 && std::islower(static_cast<unsigned char>(name[i - 1])) && std::isupper(c)) {
            out += '_';
            out += static_cast<char>(std::tolower(c));
            while (i + 1 < name.size() && std::isupper(static_cast<unsigned char>(name[i + 1])))
                out += static_cast<char>(std::tolower(static_cast<unsigned char>(name[++i])));
        } else {
            out += name[i];
        }
    }
    return out;
}
}  // namespace

std::string XmlContext::propertyName(const pugi::xml_node &property) const {
    const std::string name = property.attribute("name").value();
    if (!isBeforeVersion2(property)) return name;
    const std::string upgraded = snakeCase(name);
    const pugi::xml_node owner = property.parent();
    if (upgraded == "diffuse_reflectance" && std::string(owner.name()) == "bsdf" &&
        std::string(owner.attribute("type").value()) == "diffuse")
        return "reflectance";
    return upgraded;
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
        const std::string name = ctx.propertyName(child);
        if (name.empty()) ctx.fail(child, "property without a name attribute");
        if (m_props.count(name)) ctx.fail(child, "property \"" + name + "\" given twice");
        m_props[name] = child;
    }
}

pugi::xml_node XmlProps::find(const std::string &name, const char *tag, const char *alsoTag) {
    const auto it = m_props.find(name);
    if (it == m_props.end()) return {};
    m_used.insert(name);
    const std::string given = it->second.name();
    if (given != tag && !(alsoTag && given == alsoTag))
        m_ctx.fail(it->second, "property \"" + name + "\" must be a <" + tag + ">" +
                                   (alsoTag ? std::string(" or an <") + alsoTag + ">" : std::string()));
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

Vec3f XmlProps::parseSpectrum(const pugi::xml_node &node, const std::string &text, SpectrumUse use) const {
    std::vector<float> wavelengths, values;
    std::string entry;
    std::istringstream in(text);
    while (std::getline(in, entry, ',')) {
        const size_t colon = entry.find(':');
        if (colon == std::string::npos)
            m_ctx.fail(node, "expected wavelength:value pairs (\"400:0.2, 500:0.4\"), got \"" + entry + "\"");
        const auto trimmed = [](const std::string &t) {
            const size_t first = t.find_first_not_of(" \t\r\n"), last = t.find_last_not_of(" \t\r\n");
            return first == std::string::npos ? std::string() : t.substr(first, last - first + 1);
        };
        const float nm = parseFloat(node, trimmed(entry.substr(0, colon)));
        const float v = parseFloat(node, trimmed(entry.substr(colon + 1)));
        if (!(nm > 0.f) || (!wavelengths.empty() && !(nm > wavelengths.back())))
            m_ctx.fail(node, "the wavelengths of a <spectrum> must be positive and increase, as in Mitsuba");
        wavelengths.push_back(nm);
        values.push_back(v);
    }
    if (wavelengths.size() < 2) m_ctx.fail(node, "a <spectrum> given per wavelength needs at least two of them");
    return spectrumToRgb(wavelengths, values, use);
}

float XmlProps::getFloat(const std::string &name, float def) {
    // Mitsuba reads an <integer> where it reads a float (Properties::get converts it).
    const auto node = find(name, "float", "integer");
    if (!node) return def;
    const std::string text = m_ctx.attr(node, "value");
    return std::string(node.name()) == "integer" ? static_cast<float>(parseInt(node, text)) : parseFloat(node, text);
}

float XmlProps::getFloatRequired(const std::string &name) {
    if (!m_props.count(name)) m_ctx.fail(m_element, "missing <float name=\"" + name + "\" value=\"...\"/>");
    return getFloat(name, 0.f);
}

int XmlProps::getInt(const std::string &name, int def) {
    const auto node = find(name, "integer");
    return node ? parseInt(node, m_ctx.attr(node, "value")) : def;
}

int XmlProps::parseInt(const pugi::xml_node &node, const std::string &text) const {
    // Mitsuba skips white space around the digits.
    const size_t first = text.find_first_not_of(" \t\r\n"), last = text.find_last_not_of(" \t\r\n");
    const std::string digits = first == std::string::npos ? "" : text.substr(first, last - first + 1);
    errno = 0;
    char *end = nullptr;
    const long long v = std::strtoll(digits.c_str(), &end, 10);
    if (digits.empty() || *end != '\0' || errno == ERANGE || v < -2147483647LL || v > 2147483647LL)
        m_ctx.fail(node, "expected an integer, got \"" + text + "\"");
    return static_cast<int>(v);
}

bool XmlProps::getBool(const std::string &name, bool def) {
    const auto node = find(name, "boolean");
    if (!node) return def;
    std::string text = m_ctx.attr(node, "value");
    // Mitsuba compares without case ("True" is true).
    std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::tolower(c); });
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
    if (tag == "float" || tag == "integer") {
        const std::string text = m_ctx.attr(it->second, "value");
        const float v = tag == "float" ? parseFloat(it->second, text) : static_cast<float>(parseInt(it->second, text));
        return {v, v, v};
    }
    if (tag == "spectrum") {
        // A constant spectrum is that value in RGB too; one given per wavelength becomes RGB as Mitsuba's RGB
        // variants make it (spectrum_rgb.h), as light inside an <emitter> and as a reflectance elsewhere.
        if (it->second.attribute("filename"))
            m_ctx.fail(it->second, "property \"" + name + "\": a <spectrum> read from a file is not read here: give "
                                   "its values (value=\"400:0.2, 500:0.4, ...\") or an <rgb>");
        const std::string value = m_ctx.attr(it->second, "value");
        if (!isPerWavelength(it->second)) {
            const float v = parseFloat(it->second, value);
            return {v, v, v};
        }
        bool emission = false;
        for (pugi::xml_node n = m_element; n && !emission; n = n.parent()) emission = std::string(n.name()) == "emitter";
        return parseSpectrum(it->second, value, emission ? SpectrumUse::Emission : SpectrumUse::Reflectance);
    }
    if (tag != "rgb")
        m_ctx.fail(it->second, "property \"" + name + "\" must be an <rgb>, a <spectrum>, a <float> or an <integer>");
    return parseTriple(it->second, m_ctx.attr(it->second, "value"));
}

Vec3f XmlProps::getPoint(const std::string &name, const Vec3f &def) {
    const auto node = find(name, "point", "vector");  // one type in Mitsuba's Properties
    if (!node) return def;
    if (node.attribute("value")) return parseTriple(node, m_ctx.attr(node, "value"));
    const auto coord = [&](const char *a) {
        return node.attribute(a) ? parseFloat(node, m_ctx.attr(node, a)) : 0.f;
    };
    return {coord("x"), coord("y"), coord("z")};
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
