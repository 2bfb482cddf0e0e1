#include "ply_reader.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "error.h"
#include "ply_header.h"

namespace mcval {

namespace {

using namespace ply;

/// What reading a value gave: the value, the end of the data (or of the ascii line), or a bad token.
enum class Got { Value, End, Bad };

/// Values of binary records, in the file's byte order.
class BinarySource {
public:
    static constexpr bool kAscii = false;
    BinarySource(std::string_view data, bool bigEndian) : m_data(data), m_bigEndian(bigEndian) {}
    bool nextRecord() { return true; }  // records have no delimiter
    bool recordDone() const { return true; }
    size_t line() const { return 0; }
    std::string_view badToken() const { return {}; }

    /// The next value as a double (exact for every type of kTypes).
    Got value(const ScalarType &t, double &out) {
        if (m_data.size() - m_pos < size_t(t.size)) return Got::End;
        uint64_t bits = 0;
        for (int i = 0; i < t.size; ++i)
            bits |= uint64_t(uint8_t(m_data[m_pos + (m_bigEndian ? t.size - 1 - i : i)])) << (8 * i);
        m_pos += t.size;
        if (!t.isInteger) {
            if (t.size == 4) {
                const auto u = uint32_t(bits);
                float f;
                std::memcpy(&f, &u, 4);
                out = f;
            } else {
                std::memcpy(&out, &bits, 8);
            }
            return Got::Value;
        }
        const bool negative = t.isSigned && (bits >> (8 * t.size - 1)) != 0;
        out = negative ? double(bits) - std::ldexp(1.0, 8 * t.size) : double(bits);
        return Got::Value;
    }
    /// Skips n values of type t.
    Got skip(const ScalarType &t, uint64_t n) {
        if (n > (m_data.size() - m_pos) / size_t(t.size)) return Got::End;
        m_pos += n * t.size;
        return Got::Value;
    }

private:
    std::string_view m_data;
    bool m_bigEndian;
    size_t m_pos = 0;
};

/// Values of ascii records, one record per non-blank line.
class AsciiSource {
public:
    static constexpr bool kAscii = true;
    AsciiSource(std::string_view data, size_t firstLine) : m_data(data), m_line(firstLine - 1) {}
    /// Moves to the next non-blank line; false at the end of the file.
    bool nextRecord() {
        do {
            if (m_pos >= m_data.size()) return false;
            const size_t end = std::min(m_data.find('\n', m_pos), m_data.size());
            m_words = splitWords(m_data.substr(m_pos, end - m_pos));
            m_pos = end + 1;
            ++m_line;
        } while (m_words.empty());
        m_next = 0;
        return true;
    }
    bool recordDone() const { return m_next == m_words.size(); }
    size_t line() const { return m_line; }
    std::string_view badToken() const { return m_words[m_next - 1]; }

    /// The next value of the line, parsed as type t (integers range-checked against it).
    Got value(const ScalarType &t, double &out) {
        if (m_next == m_words.size()) return Got::End;
        std::string_view s = m_words[m_next++];
        if (s.size() > 1 && s[0] == '+') s.remove_prefix(1);  // from_chars takes no plus sign
        const char *first = s.data(), *last = s.data() + s.size();
        std::from_chars_result r{};
        if (t.isInteger) {
            int64_t v = 0;
            r = std::from_chars(first, last, v);
            const double lo = t.isSigned ? -std::ldexp(1.0, 8 * t.size - 1) : 0.0;
            const double hi = std::ldexp(1.0, 8 * t.size - (t.isSigned ? 1 : 0)) - 1.0;
            out = double(v);
            if (out < lo || out > hi) return Got::Bad;
        } else if (t.size == 4) {
            float v = 0.f;
            r = std::from_chars(first, last, v);
            out = v;
        } else {
            r = std::from_chars(first, last, out);
        }
        return r.ec == std::errc() && r.ptr == last ? Got::Value : Got::Bad;
    }
    Got skip(const ScalarType &t, uint64_t n) {
        double v;
        for (uint64_t i = 0; i < n; ++i)
            if (const Got got = value(t, v); got != Got::Value) return got;
        return Got::Value;
    }

private:
    std::string_view m_data;
    size_t m_pos = 0, m_line, m_next = 0;
    std::vector<std::string_view> m_words;
};

/// Reads the records of one element; vertices and faces go into `mesh`, others are skipped.
template <class Source>
void readElement(const std::string &path, Source &src, const Element &el, uint64_t vertexCount, bool hasNormals,
                 Mesh &mesh) {
    if (el.properties.empty()) return;  // its records take no bytes and no lines
    const bool isVertex = el.name == "vertex";
    for (uint64_t i = 0; i < el.count; ++i) {
        // Messages are built only on failure: this loop runs once per vertex and face.
        const auto where = [&] {
            return el.name + " " + std::to_string(i) +
                   (Source::kAscii ? " (line " + std::to_string(src.line()) + ")" : std::string());
        };
        const auto truncated = [&] {
            fail(path, "the file ends inside the " + el.name + " data (" + el.name + " " + std::to_string(i) +
                           " of " + std::to_string(el.count) + ")");
        };
        const auto check = [&](Got got, const ScalarType &t, const char *what, const std::string &name) {
            if (got == Got::Value) return;
            if (!Source::kAscii) truncated();
            if (got == Got::End) fail(path, where() + ": too few values on the line");
            fail(path, where() + ": \"" + std::string(src.badToken()) + "\" is not a valid " + t.name + " (" + what +
                           " " + name + ")");
        };
        const auto read = [&](const ScalarType &t, const char *what, const std::string &name) {
            double v = 0.0;
            check(src.value(t, v), t, what, name);
            return v;
        };
        if (!src.nextRecord()) truncated();
        float slots[6] = {0, 0, 0, 0, 0, 0};
        for (const Property &p : el.properties) {
            if (!p.isList) {
                const double v = read(p.type, "property", p.name);
                if (p.role >= 0 && p.role < kFaceIndices) slots[p.role] = float(v);
                continue;
            }
            const double n = read(p.countType, "length of list", p.name);
            if (n < 0) fail(path, where() + ": list " + p.name + " has negative length " + std::to_string(int64_t(n)));
            if (p.role != kFaceIndices) {
                check(src.skip(p.type, uint64_t(n)), p.type, "an item of list", p.name);
                continue;
            }
            if (n < 3) fail(path, where() + ": a face needs at least 3 vertices, this one has " + std::to_string(int(n)));
            uint32_t first = 0, previous = 0;
            for (uint64_t k = 0; k < uint64_t(n); ++k) {
                const double index = read(p.type, "an item of list", p.name);
                if (index < 0 || index >= double(vertexCount))
                    fail(path, where() + ": vertex index " + std::to_string(int64_t(index)) +
                                   " out of range (the mesh has " + std::to_string(vertexCount) + " vertices)");
                const auto current = uint32_t(index);
                if (k == 0) first = current;
                if (k >= 2) mesh.indices.insert(mesh.indices.end(), {first, previous, current});
                previous = current;
                if (mesh.indices.size() > 3 * kMaxCount) fail(path, where() + ": more than 2^28 triangles");
            }
        }
        if (!src.recordDone()) fail(path, where() + ": more values on the line than the header declares");
        if (!isVertex) continue;
        if (!std::isfinite(slots[0]) || !std::isfinite(slots[1]) || !std::isfinite(slots[2]))
            fail(path, where() + ": position is not finite (" + std::to_string(slots[0]) + ", " +
                           std::to_string(slots[1]) + ", " + std::to_string(slots[2]) + ")");
        mesh.positions.emplace_back(slots[0], slots[1], slots[2]);
        if (!hasNormals) continue;
        if (!std::isfinite(slots[3]) || !std::isfinite(slots[4]) || !std::isfinite(slots[5]))
            fail(path, where() + ": normal is not finite");
        mesh.normals.emplace_back(slots[3], slots[4], slots[5]);
    }
}

}  // namespace

Mesh readPly(const std::string &path, std::string_view bytes) {
    Header h = parseHeader(path, bytes);
    Element *vertex = nullptr, *face = nullptr;
    bool hasIndices = false;
    uint64_t minBytes = 0;  // the least the declared records can take
    for (Element &el : h.elements) {
        if (el.name == "vertex") vertex = &el;
        if (el.name == "face") face = &el;
        uint64_t perRecord = 0;  // binary: bytes; ascii: values (each takes at least 2 bytes)
        for (Property &p : el.properties) {
            for (int s = 0; s < 6; ++s)
                if (&el == vertex && p.name == kSlotNames[s]) p.role = s;
            if (&el == face && p.isList && !hasIndices && (p.name == "vertex_indices" || p.name == "vertex_index"))
                p.role = kFaceIndices;  // the first of the two names counts
            hasIndices |= p.role == kFaceIndices;
            if (p.role >= 0 && p.role < kFaceIndices && p.isList) fail(path, "vertex property " + p.name + " is a list");
            if (p.role == kFaceIndices && !p.type.isInteger) fail(path, "the face indices " + p.name + " are not integers");
            const uint64_t items = p.role == kFaceIndices ? 3 : 0;  // a face has at least 3
            perRecord += h.ascii ? 1 + (p.isList ? items : 0)
                                 : (p.isList ? p.countType.size + items * p.type.size : p.type.size);
        }
        minBytes += el.count * (h.ascii ? 2 * perRecord : perRecord);
        const uint64_t available = bytes.size() - h.dataOffset + (h.ascii ? 1 : 0);  // last line may lack '\n'
        if (minBytes > available)
            fail(path, "element " + el.name + " declares " + std::to_string(el.count) + " records, but the " +
                           std::to_string(bytes.size() - h.dataOffset) +
                           " bytes after the header cannot hold them (the file is truncated or its header wrong)");
    }
    if (!vertex) fail(path, "the file has no vertex element");
    if (!face) fail(path, "the file has no face element (points alone are no surface)");
    int slotsFound[6] = {0, 0, 0, 0, 0, 0};
    for (const Property &p : vertex->properties)
        if (p.role >= 0) ++slotsFound[p.role];
    for (int s = 0; s < 3; ++s)
        if (!slotsFound[s]) fail(path, std::string("the vertex element has no property ") + kSlotNames[s]);
    const int normalSlots = slotsFound[3] + slotsFound[4] + slotsFound[5];
    if (normalSlots != 0 && normalSlots != 3) fail(path, "vertex normals need all three of nx, ny, nz");
    if (!hasIndices) fail(path, "the face element has no list vertex_indices (or vertex_index)");

    Mesh mesh;
    mesh.positions.reserve(vertex->count);
    if (normalSlots == 3) mesh.normals.reserve(vertex->count);
    mesh.indices.reserve(3 * face->count);
    const std::string_view data = bytes.substr(h.dataOffset);
    if (h.ascii) {
        size_t headerLines = 0;
        for (size_t i = 0; i < h.dataOffset; ++i) headerLines += bytes[i] == '\n';
        AsciiSource src(data, headerLines + 1);
        for (const Element &el : h.elements) readElement(path, src, el, vertex->count, normalSlots == 3, mesh);
    } else {
        BinarySource src(data, h.bigEndian);
        for (const Element &el : h.elements) readElement(path, src, el, vertex->count, normalSlots == 3, mesh);
    }
    return mesh;  // bytes after the last record are tolerated, as by most readers
}

}  // namespace mcval
