// Typed access to the property children of one Mitsuba XML element, with file:line errors.
#pragma once

#include <list>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <pugixml.hpp>

#include "spectrum_rgb.h"
#include "transform.h"
#include "vector.h"

namespace mcval {

/// The parse state shared by all elements of one scene: its file's name and text (for line numbers), the
/// files its <include>s brought in, where relative file names are looked for, and the $parameters.
struct XmlContext {
    std::string file;
    std::string text;
    std::map<std::string, std::string> params;
    /// Mitsuba's file resolver: every <path> folder so far (the newest first), then the scene file's folder.
    std::vector<std::string> folders;
    /// A file that <include> brought in, parsed once and kept for its nodes' file and line.
    struct Included {
        pugi::xml_document doc;
        std::string file, text;
    };
    std::list<Included> included;

    int line(const pugi::xml_node &node) const;
    /// " at line N": where `node` stands, for messages that name several elements.
    std::string at(const pugi::xml_node &node) const { return " at line " + std::to_string(line(node)); }
    /// The file the node was read from: the scene file or an included one.
    const std::string &fileOf(const pugi::xml_node &node) const;
    /// `name` as Mitsuba finds it: absolute as it is, else in the first of `folders` that has it (the scene
    /// file's folder when none does, so that the error names where it was expected).
    std::string resolve(const std::string &name) const { return resolve(name, folders); }
    /// The same with the folders the resolver held at an earlier element (one read after the whole file).
    static std::string resolve(const std::string &name, const std::vector<std::string> &folders);
    /// Throws SceneError at the node's line.
    [[noreturn]] void fail(const pugi::xml_node &node, const std::string &message) const;
    /// A property element's name as Mitsuba 3 reads it: in a file older than version 2.0.0 (Mitsuba 0.5, 0.6)
    /// upgraded as Mitsuba does (camelCase to snake_case, a diffuse bsdf's diffuse_reflectance to reflectance).
    std::string propertyName(const pugi::xml_node &property) const;
    /// An attribute's value with $name parameters substituted.
    std::string attr(const pugi::xml_node &node, const char *name) const;
};

/// The numbers of a value attribute ("1, 2, 3" or "1 2 3"), as text.
std::vector<std::string> splitNumbers(const std::string &text);

/// Whether a <spectrum> is given per wavelength ("400:0.2, 700:0.8" or a file) rather than as one value.
bool isPerWavelength(const pugi::xml_node &spectrum);

/// The `<float name=...>`-style children of an element. Each get* consumes one; finish() rejects leftovers.
class XmlProps {
public:
    XmlProps(const XmlContext &ctx, const pugi::xml_node &element);

    /// A <float>, or an <integer> (Mitsuba converts it).
    float getFloat(const std::string &name, float def);
    float getFloatRequired(const std::string &name);
    int getInt(const std::string &name, int def);
    bool getBool(const std::string &name, bool def);
    std::string getString(const std::string &name, const std::string &def);
    std::string getStringRequired(const std::string &name);
    /// `<rgb>` with "r, g, b" or a single value, a `<float>` or `<integer>` gray, or a constant `<spectrum>`.
    Vec3f getColor(const std::string &name, const Vec3f &def);
    /// `<point>` (or `<vector>`, the same type to Mitsuba) with value="x, y, z" or x/y/z attributes.
    Vec3f getPoint(const std::string &name, const Vec3f &def);
    Transform getTransform(const std::string &name);
    /// Whether the element has a property called `name`.
    bool has(const std::string &name) const { return m_props.count(name) > 0; }
    /// The property element called `name`, or an empty node.
    pugi::xml_node node(const std::string &name) const {
        const auto it = m_props.find(name);
        return it == m_props.end() ? pugi::xml_node() : it->second;
    }
    /// Accepts a property that cannot change our answer (whatever its type) without reading it.
    void ignore(const std::string &name) {
        if (m_props.count(name)) m_used.insert(name);
    }

    /// Throws at the property's line (the element's if it was not given) unless every component of
    /// `value` lies in [lo, hi]; NaN never does.
    void requireRange(const std::string &name, const Vec3f &value, float lo, float hi) const;
    void requireRange(const std::string &name, float value, float lo, float hi) const {
        requireRange(name, Vec3f(value, value, value), lo, hi);
    }
    void requireRange(const std::string &name, int value, int lo, int hi) const;

    /// The element whose properties these are.
    const pugi::xml_node &element() const { return m_element; }
    /// Child elements that are objects (film, sampler, bsdf, ref, ...), for the caller to handle.
    const std::vector<pugi::xml_node> &objects() const { return m_objects; }
    /// Throws if a property was given that nothing asked for.
    void finish(const std::string &expected) const;
    /// Throws at the line of property `name` (the element's if it was not given).
    [[noreturn]] void failAt(const std::string &name, const std::string &message) const;

private:
    /// The property `name` (marked used), which must be a <tag> (or an <alsoTag>); empty if not given.
    pugi::xml_node find(const std::string &name, const char *tag, const char *alsoTag = nullptr);
    int parseInt(const pugi::xml_node &node, const std::string &text) const;
    float parseFloat(const pugi::xml_node &node, const std::string &text) const;
    Vec3f parseTriple(const pugi::xml_node &node, const std::string &text) const;
    /// "400:0.2, 500:0.4, ..." (increasing wavelengths in nm, at least two) as RGB.
    Vec3f parseSpectrum(const pugi::xml_node &node, const std::string &text, SpectrumUse use) const;
    Transform parseTransform(const pugi::xml_node &node) const;
    Transform parseTransformStep(const pugi::xml_node &step) const;

    const XmlContext &m_ctx;
    pugi::xml_node m_element;
    std::map<std::string, pugi::xml_node> m_props;
    std::set<std::string> m_used;
    std::vector<pugi::xml_node> m_objects;
};

}  // namespace mcval
