#include "serialized_reader.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <functional>
#include <type_traits>
#include <vector>

#include <zlib.h>

#include "error.h"

namespace mcval {

namespace {

constexpr uint16_t kMagic = 0x041C;
// Mitsuba 3.9 reads versions 3 and 4; its development branch's version 5 is another (packed) layout.
constexpr uint16_t kVersion3 = 3, kVersion4 = 4;
constexpr uint32_t kHasNormals = 0x1, kHasTexcoords = 0x2, kHasColors = 0x8, kDoublePrecision = 0x2000;
/// At most as many vertices and triangles as the PLY reader takes.
constexpr uint64_t kMaxCount = uint64_t(1) << 28;
/// Longest shape name read (version 4 stores a null-terminated one).
constexpr size_t kMaxNameBytes = 1 << 16;
/// Deflate's largest expansion (zlib's technical details: 1032 to 1).
constexpr uint64_t kMaxInflateRatio = 1032;
/// Values read per step: an array grows with the data that is there, never with what a count claims.
constexpr size_t kChunkValues = size_t(1) << 16;

[[noreturn]] void fail(const std::string &path, const std::string &message) { throw SceneError(path, 0, message); }

/// A little-endian integer or IEEE float at `at`.
template <typename T>
T littleEndian(std::string_view bytes, size_t at) {
    uint64_t bits = 0;
    for (size_t i = 0; i < sizeof(T); ++i) bits |= uint64_t(uint8_t(bytes[at + i])) << (8 * i);
    if constexpr (std::is_floating_point_v<T>) {
        using Bits = std::conditional_t<sizeof(T) == 4, uint32_t, uint64_t>;
        const Bits exact = Bits(bits);
        T v;
        std::memcpy(&v, &exact, sizeof(T));
        return v;
    } else {
        return T(bits);
    }
}

/// The zlib stream of one shape, inflated on demand.
class Inflater {
public:
    Inflater(const std::string &path, std::string_view compressed) : m_path(path) {
        // zlib takes at most 4 GiB of input at a time; mesh files are at most 2 GiB (mesh.cpp).
        if (compressed.size() > UINT_MAX) fail(path, "more than 4 GiB of compressed data");
        if (inflateInit(&m_z) != Z_OK) fail(path, "cannot start zlib decompression");
        m_z.next_in = reinterpret_cast<Bytef *>(const_cast<char *>(compressed.data()));
        m_z.avail_in = uInt(compressed.size());
    }
    ~Inflater() { inflateEnd(&m_z); }
    Inflater(const Inflater &) = delete;
    Inflater &operator=(const Inflater &) = delete;

    /// Exactly n bytes into dst; `what` names them if the stream ends or is corrupt first.
    void read(void *dst, size_t n, const std::string &what) {
        auto *out = static_cast<Bytef *>(dst);
        while (n > 0) {
            m_z.next_out = out;
            m_z.avail_out = uInt(std::min<size_t>(n, UINT_MAX));
            const uInt asked = m_z.avail_out;
            const int status = ::inflate(&m_z, Z_NO_FLUSH);
            const size_t got = asked - m_z.avail_out;
            out += got;
            n -= got;
            if (n == 0) return;
            // The stream's end, or no progress: the input ran out before the data it promised.
            if (status == Z_STREAM_END || (status == Z_BUF_ERROR && got == 0))
                fail(m_path, "the compressed data ends before " + what + " (truncated file or a count too large)");
            if (status != Z_OK && status != Z_BUF_ERROR)
                fail(m_path, "corrupt compressed data while reading " + what + ": " +
                                 (m_z.msg ? m_z.msg : "zlib error " + std::to_string(status)));
        }
    }

    /// Requires the stream to end here, its checksum (Adler-32) right: this catches damage that left
    /// every value plausible, and data past what the counts said.
    void finish(const std::string &what) {
        unsigned char extra = 0;
        m_z.next_out = &extra;
        m_z.avail_out = 1;
        const int status = ::inflate(&m_z, Z_FINISH);
        if (status == Z_STREAM_END && m_z.avail_out == 1) return;
        if (status == Z_DATA_ERROR)
            fail(m_path, "corrupt compressed data after " + what + ": " + (m_z.msg ? m_z.msg : "zlib data error"));
        fail(m_path, m_z.avail_out == 0 ? "the compressed data goes on after " + what + " (counts too small)"
                                        : "the compressed data ends without its checksum after " + what);
    }

    /// One little-endian value.
    template <typename T>
    T value(const std::string &what) {
        unsigned char raw[sizeof(T)];
        read(raw, sizeof(T), what);
        return littleEndian<T>(std::string_view(reinterpret_cast<const char *>(raw), sizeof(T)), 0);
    }

    /// `count` values of T, passed to `take` one by one; read in steps, so memory follows the data that is
    /// there, never what a count claims.
    template <typename T, typename Take>
    void values(uint64_t count, const std::string &what, Take take) {
        std::vector<unsigned char> raw;
        for (uint64_t done = 0; done < count;) {
            const size_t step = size_t(std::min<uint64_t>(count - done, kChunkValues));
            raw.resize(step * sizeof(T));
            read(raw.data(), raw.size(), what);
            const std::string_view view(reinterpret_cast<const char *>(raw.data()), raw.size());
            for (size_t i = 0; i < step; ++i) take(littleEndian<T>(view, i * sizeof(T)));
            done += step;
        }
    }

private:
    std::string m_path;
    z_stream m_z{};
};

/// `count` vertices of `dim` values (float32, or float64 in files with kDoublePrecision), each vertex
/// passed to `take` as float32 (a null `take` reads past them).
void readVertices(Inflater &in, uint64_t count, int dim, bool doubles, const std::string &what,
                  const std::function<void(const float *)> &take) {
    float vertex[3];
    int filled = 0;
    const auto one = [&](auto v) {
        vertex[filled++] = float(v);
        if (filled == dim) {
            if (take) take(vertex);
            filled = 0;
        }
    };
    if (doubles) in.values<double>(count * dim, what, one);
    else in.values<float>(count * dim, what, one);
}

/// Where shape `index` starts: 0 for the first; otherwise the end-of-file table (version 4: u64
/// offsets, version 3: u32 offsets; the shape count, u32, last).
size_t shapeOffset(const std::string &path, std::string_view bytes, uint16_t version, uint32_t index) {
    if (index == 0) return 0;
    if (bytes.size() < 8) fail(path, "too short for the table of shape offsets at its end");
    const uint32_t count = littleEndian<uint32_t>(bytes, bytes.size() - 4);
    if (index >= count)
        fail(path, "shape_index " + std::to_string(index) + " is out of range: the file holds " +
                       std::to_string(count) + " shape(s), numbered from 0");
    const size_t width = version == kVersion4 ? 8 : 4;
    if (uint64_t(count) * width > bytes.size() - 4)
        fail(path, "its table of " + std::to_string(count) + " shape offsets is longer than the file");
    const size_t at = bytes.size() - 4 - width * size_t(count - index);
    const uint64_t offset = width == 8 ? littleEndian<uint64_t>(bytes, at) : littleEndian<uint32_t>(bytes, at);
    if (offset > bytes.size() - 4 - width * size_t(count) || bytes.size() - 4 - width * size_t(count) - offset < 4)
        fail(path, "the offset of shape " + std::to_string(index) + " (" + std::to_string(offset) +
                       ") lies past the shapes' data");
    return size_t(offset);
}

}  // namespace

Mesh readSerialized(const std::string &path, std::string_view bytes, uint32_t shapeIndex) {
    if (bytes.size() < 4) fail(path, "too short for a serialized mesh header (4 bytes)");
    const uint16_t version = littleEndian<uint16_t>(bytes, 2);
    if (littleEndian<uint16_t>(bytes, 0) != kMagic) fail(path, "not a serialized mesh: expected the header 0x041C");
    if (version != kVersion3 && version != kVersion4)
        fail(path, "serialized format version " + std::to_string(version) + ": expected 3 or 4 (Mitsuba 3's)");
    const size_t start = shapeOffset(path, bytes, version, shapeIndex);
    const std::string shape = "shape " + std::to_string(shapeIndex);
    if (shapeIndex != 0 && (littleEndian<uint16_t>(bytes, start) != kMagic ||
                            littleEndian<uint16_t>(bytes, start + 2) != version))
        fail(path, shape + " at offset " + std::to_string(start) + " does not start with the file's header");

    Inflater in(path, bytes.substr(start + 4));
    const uint32_t flags = in.value<uint32_t>(shape + "'s flags");
    if (version == kVersion4) {
        std::string name;
        for (char c; (c = char(in.value<uint8_t>(shape + "'s name"))) != '\0';) {
            if (name.size() == kMaxNameBytes)
                fail(path, shape + "'s name is longer than " + std::to_string(kMaxNameBytes) +
                               " bytes or not terminated");
            name += c;
        }
    }
    const uint64_t vertexCount = in.value<uint64_t>(shape + "'s vertex count");
    const uint64_t faceCount = in.value<uint64_t>(shape + "'s triangle count");
    if (vertexCount > kMaxCount || faceCount > kMaxCount)
        fail(path, shape + " has " + std::to_string(vertexCount) + " vertices and " + std::to_string(faceCount) +
                       " triangles: at most 2^28 of each are supported");
    if (faceCount == 0) fail(path, shape + " has no triangles");

    // Deflate inflates at most 1032 bytes from one: counts that need more than the file holds are false.
    const uint64_t perVertex = (3 + (flags & kHasNormals ? 3 : 0) + (flags & kHasTexcoords ? 2 : 0) +
                                (flags & kHasColors ? 3 : 0)) * (flags & kDoublePrecision ? 8 : 4);
    const uint64_t claimed = vertexCount * perVertex + faceCount * 12;
    if (claimed / kMaxInflateRatio > bytes.size() - start)
        fail(path, shape + " claims " + std::to_string(vertexCount) + " vertices and " + std::to_string(faceCount) +
                       " triangles (" + std::to_string(claimed) + " bytes), more than its " +
                       std::to_string(bytes.size() - start) + " compressed bytes can hold");

    const bool doubles = (flags & kDoublePrecision) != 0;  // as in Mitsuba, double wins if both are set
    Mesh mesh;
    const auto into = [](std::vector<Vec3f> &out) {
        return [&out](const float *v) { out.emplace_back(v[0], v[1], v[2]); };
    };
    readVertices(in, vertexCount, 3, doubles, shape + "'s vertex positions", into(mesh.positions));
    if (flags & kHasNormals)
        readVertices(in, vertexCount, 3, doubles, shape + "'s vertex normals", into(mesh.normals));
    if (flags & kHasTexcoords) readVertices(in, vertexCount, 2, doubles, shape + "'s texture coordinates", nullptr);
    if (flags & kHasColors) readVertices(in, vertexCount, 3, doubles, shape + "'s vertex colours", nullptr);
    // Mitsuba 3 reads u32 indices whatever the vertex count (its meshes index with 32 bits).
    in.values<uint32_t>(3 * faceCount, shape + "'s triangle indices", [&](uint32_t i) {
        if (i >= vertexCount)
            fail(path, shape + ": triangle " + std::to_string(mesh.indices.size() / 3) + " uses vertex " +
                           std::to_string(i) + ", but there are " + std::to_string(vertexCount));
        mesh.indices.push_back(i);
    });
    in.finish(shape + "'s triangle indices");
    return mesh;
}

}  // namespace mcval
