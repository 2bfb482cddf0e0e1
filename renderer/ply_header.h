// The header of a PLY file: its format, elements and properties, checked line by line.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mcval::ply {

/// A scalar type of the header: byte size, integer or floating point, signedness.
struct ScalarType {
    const char *name;
    int size;
    bool isInteger;
    bool isSigned;
};

/// What a property is to us: a coordinate slot (x, y, z, nx, ny, nz), the face's index list, or skipped.
constexpr int kSkip = -1, kFaceIndices = 6;
inline constexpr const char *kSlotNames[6] = {"x", "y", "z", "nx", "ny", "nz"};

struct Property {
    std::string name;
    ScalarType type{};
    bool isList = false;
    ScalarType countType{};
    int role = kSkip;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

/// A parsed header; dataOffset is where the element data starts.
struct Header {
    bool ascii = false, bigEndian = false;
    std::vector<Element> elements;
    size_t dataOffset = 0;
};

/// Parses and checks the header at the start of `data`; `path` only names the file in errors.
/// Throws SceneError (no format line, unknown keyword or type, counts beyond the limits, no end_header).
Header parseHeader(const std::string &path, std::string_view data);

/// The blank-separated words of a line.
std::vector<std::string_view> splitWords(std::string_view line);

/// Throws SceneError(path, 0, message).
[[noreturn]] void fail(const std::string &path, const std::string &message);

/// Largest number of vertices, faces or triangles of one file.
constexpr uint64_t kMaxCount = uint64_t(1) << 28;

}  // namespace mcval::ply
