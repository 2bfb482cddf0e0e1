#include "ply_header.h"

#include <algorithm>
#include <charconv>

#include "error.h"

namespace mcval::ply {

namespace {

// The PLY 1.0 names and the sized aliases Mitsuba accepts too.
constexpr ScalarType kTypes[] = {
    {"char", 1, true, true},    {"int8", 1, true, true},     {"uchar", 1, true, false}, {"uint8", 1, true, false},
    {"short", 2, true, true},   {"int16", 2, true, true},    {"ushort", 2, true, false}, {"uint16", 2, true, false},
    {"int", 4, true, true},     {"int32", 4, true, true},    {"uint", 4, true, false},  {"uint32", 4, true, false},
    {"float", 4, false, true},  {"float32", 4, false, true}, {"double", 8, false, true}, {"float64", 8, false, true}};

constexpr size_t kMaxHeaderBytes = 65536;  // a real header is a few hundred bytes

const ScalarType *findType(std::string_view name) {
    for (const ScalarType &t : kTypes)
        if (name == t.name) return &t;
    return nullptr;
}

/// One header line (already split), added to `h`; `where` prefixes errors.
void parseHeaderLine(const std::string &path, const std::string &where, const std::vector<std::string_view> &w,
                     bool &sawFormat, Header &h) {
    const auto type = [&](std::string_view name) {
        const ScalarType *t = findType(name);
        if (!t) fail(path, where + "unknown type \"" + std::string(name) + "\"");
        return *t;
    };
    if (w[0] == "format") {
        if (sawFormat) fail(path, where + "a second format line");
        if (w.size() != 3) fail(path, where + "expected \"format <ascii|binary_little_endian|binary_big_endian> 1.0\"");
        if (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")
            fail(path, where + "unknown format \"" + std::string(w[1]) + "\"");
        if (w[2] != "1.0") fail(path, where + "unknown format version \"" + std::string(w[2]) + "\" (expected 1.0)");
        h.ascii = w[1] == "ascii";
        h.bigEndian = w[1] == "binary_big_endian";
        sawFormat = true;
    } else if (w[0] == "element") {
        if (!sawFormat) fail(path, where + "element before the format line");
        if (w.size() != 3) fail(path, where + "expected \"element <name> <count>\"");
        Element el{std::string(w[1]), 0, {}};
        const auto [end, ec] = std::from_chars(w[2].data(), w[2].data() + w[2].size(), el.count);
        if (ec != std::errc() || end != w[2].data() + w[2].size())
            fail(path, where + "element count \"" + std::string(w[2]) + "\" is not a number");
        if (el.count > kMaxCount)
            fail(path, where + "element " + el.name + " has " + std::string(w[2]) + " records; at most 2^28 are supported");
        for (const Element &other : h.elements)
            if (other.name == el.name) fail(path, where + "a second element " + el.name);
        h.elements.push_back(std::move(el));
    } else if (w[0] == "property") {
        if (h.elements.empty()) fail(path, where + "property before any element");
        Property p;
        p.isList = w.size() >= 2 && w[1] == "list";
        if (w.size() != (p.isList ? 5u : 3u))
            fail(path, where + "expected \"property <type> <name>\" or \"property list <count type> <type> <name>\"");
        if (p.isList) {
            p.countType = type(w[2]);
            if (!p.countType.isInteger) fail(path, where + "a list count must have an integer type");
        }
        p.type = type(w[p.isList ? 3 : 1]);
        p.name = std::string(w.back());
        for (const Property &other : h.elements.back().properties)
            if (other.name == p.name) fail(path, where + "a second property " + p.name);
        h.elements.back().properties.push_back(std::move(p));
    } else {
        fail(path, where + "unknown keyword \"" + std::string(w[0]) + "\"");
    }
}

}  // namespace

Header parseHeader(const std::string &path, std::string_view data) {
    if (data.empty()) fail(path, "the file is empty");
    Header h;
    bool sawFormat = false;
    size_t pos = 0;
    for (int lineNo = 1;; ++lineNo) {
        const size_t end = data.find('\n', pos);
        if (end == std::string_view::npos || end >= kMaxHeaderBytes) {
            if (data.size() < kMaxHeaderBytes) fail(path, "the file ends inside the header (no end_header line)");
            fail(path, "header has no end_header in the first " + std::to_string(kMaxHeaderBytes) + " bytes");
        }
        const std::vector<std::string_view> words = splitWords(data.substr(pos, end - pos));
        pos = end + 1;
        if (lineNo == 1) {
            if (words.size() != 1 || words[0] != "ply") fail(path, "not a PLY file (the first line is not \"ply\")");
            continue;
        }
        if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
        if (words[0] == "end_header") break;
        parseHeaderLine(path, "header line " + std::to_string(lineNo) + ": ", words, sawFormat, h);
    }
    if (!sawFormat) fail(path, "the header has no format line");
    h.dataOffset = pos;
    return h;
}

void fail(const std::string &path, const std::string &message) { throw SceneError(path, 0, message); }

std::vector<std::string_view> splitWords(std::string_view line) {
    std::vector<std::string_view> words;
    size_t pos = 0;
    while (true) {
        pos = line.find_first_not_of(" \t\r\v\f", pos);
        if (pos == std::string_view::npos) return words;
        const size_t end = std::min(line.find_first_of(" \t\r\v\f", pos), line.size());
        words.push_back(line.substr(pos, end - pos));
        pos = end;
    }
}

}  // namespace mcval::ply
