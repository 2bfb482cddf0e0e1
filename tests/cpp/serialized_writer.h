// Writes Mitsuba .serialized files for the tests (versions 3 and 4; any field can be made wrong), so the
// reader is tested on files of our own, good and damaged.
#pragma once

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <zlib.h>

namespace mcval::test {

/// One shape's data as the file stores it; the counts default to the arrays' sizes.
struct SerializedShape {
    std::vector<double> positions, normals, texcoords, colors;  ///< 3, 3, 2, 3 per vertex
    std::vector<uint32_t> indices;
    bool doubles = false;
    std::string name = "shape";
    std::optional<uint64_t> vertexCount, faceCount;  ///< what the header claims, if not the truth
    uint16_t magic = 0x041C, version = 4;            ///< this shape's own header
};

template <class T> void putLittle(std::string &out, T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(reinterpret_cast<const char *>(b), sizeof(T));  // the test machines are little endian
}

/// The zlib stream of one shape (without its 4-byte header).
inline std::string serializedPayload(const SerializedShape &s) {
    std::string raw;
    const uint32_t flags = (s.normals.empty() ? 0 : 0x1) | (s.texcoords.empty() ? 0 : 0x2) |
                           (s.colors.empty() ? 0 : 0x8) | (s.doubles ? 0x2000 : 0x1000);
    putLittle(raw, flags);
    if (s.version >= 4) raw += s.name + '\0';
    putLittle<uint64_t>(raw, s.vertexCount.value_or(s.positions.size() / 3));
    putLittle<uint64_t>(raw, s.faceCount.value_or(s.indices.size() / 3));
    for (const auto *array : {&s.positions, &s.normals, &s.texcoords, &s.colors})
        for (double v : *array) {
            if (s.doubles) putLittle(raw, v);
            else putLittle(raw, float(v));
        }
    for (uint32_t i : s.indices) putLittle(raw, i);
    uLongf size = compressBound(uLong(raw.size()));
    std::string packed(size, '\0');
    compress2(reinterpret_cast<Bytef *>(packed.data()), &size, reinterpret_cast<const Bytef *>(raw.data()),
              uLong(raw.size()), 6);
    packed.resize(size);
    return packed;
}

/// A whole file: each shape's header and stream, then the table of offsets (u64 if the first shape is of
/// version 4, u32 for version 3) and the shape count, as Mitsuba writes them.
inline std::string serializedFile(const std::vector<SerializedShape> &shapes) {
    std::string out;
    std::vector<uint64_t> offsets;
    const uint16_t version = shapes.empty() ? 4 : shapes[0].version;
    for (const SerializedShape &s : shapes) {
        offsets.push_back(out.size());
        putLittle(out, s.magic);
        putLittle(out, s.version);
        out += serializedPayload(s);
    }
    for (uint64_t o : offsets) {
        if (version >= 4) putLittle(out, o);
        else putLittle(out, uint32_t(o));
    }
    putLittle(out, uint32_t(shapes.size()));
    return out;
}

/// A unit square in z = 0 facing +z (two triangles), moved by `dx` along x.
inline SerializedShape square(double dx = 0.0) {
    SerializedShape s;
    s.positions = {dx, 0, 0, dx + 1, 0, 0, dx + 1, 1, 0, dx, 1, 0};
    s.indices = {0, 1, 2, 0, 2, 3};
    return s;
}

}  // namespace mcval::test
