#include "obj_reader.h"

#include <cmath>
#include <cstdint>
#include <istream>
#include <unordered_map>
#include <vector>

#include <tiny_obj_loader.h>

#include "error.h"

namespace mcval {

namespace {

constexpr size_t kMaxVertices = size_t(1) << 28;

/// Lets tinyobjloader read bytes we already hold, so it never opens a file itself.
class MemoryBuffer : public std::streambuf {
public:
    explicit MemoryBuffer(std::string_view bytes) {
        char *p = const_cast<char *>(bytes.data());  // only read: the get area is never written
        setg(p, p, p + bytes.size());
    }
};

/// A face corner: 0-based position, texcoord and normal indices (-1 when absent).
struct Corner {
    int64_t v, vt, vn;
    bool operator==(const Corner &o) const { return v == o.v && vt == o.vt && vn == o.vn; }
};

struct CornerHash {
    size_t operator()(const Corner &c) const {
        return std::hash<int64_t>()(c.v) ^ (std::hash<int64_t>()(c.vt) * 0x9e3779b97f4a7c15ull) ^
               (std::hash<int64_t>()(c.vn) * 0xc2b2ae3d27d4eb4full);
    }
};

/// What the callbacks collect; the first error stops collecting (exceptions must not cross the library).
struct ObjState {
    std::vector<Vec3f> positions, normals;
    std::vector<Vec2f> texcoords;
    size_t texcoordCount = 0;
    std::unordered_map<Corner, uint32_t, CornerHash> vertexOf;  // corner -> mesh vertex
    std::vector<Corner> vertices;                               // mesh vertex -> corner
    std::vector<uint32_t> indices;
    bool everyCornerHasNormal = true, everyCornerHasTexcoord = true;
    size_t faceCount = 0;
    std::string error;
};

bool finite(float x, float y, float z) { return std::isfinite(x) && std::isfinite(y) && std::isfinite(z); }

void onVertex(void *user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z, tinyobj::real_t) {
    auto &s = *static_cast<ObjState *>(user);
    if (!s.error.empty()) return;
    if (!finite(x, y, z)) s.error = "vertex " + std::to_string(s.positions.size() + 1) + " is not finite";
    s.positions.emplace_back(x, y, z);
}

void onNormal(void *user, tinyobj::real_t x, tinyobj::real_t y, tinyobj::real_t z) {
    auto &s = *static_cast<ObjState *>(user);
    if (!s.error.empty()) return;
    if (!finite(x, y, z)) s.error = "normal " + std::to_string(s.normals.size() + 1) + " is not finite";
    s.normals.emplace_back(x, y, z);
}

void onTexcoord(void *user, tinyobj::real_t u, tinyobj::real_t v, tinyobj::real_t) {
    auto &s = *static_cast<ObjState *>(user);
    ++s.texcoordCount;
    if (!s.error.empty()) return;
    if (!std::isfinite(u) || !std::isfinite(v)) s.error = "texcoord " + std::to_string(s.texcoordCount) + " is not finite";
    // Mitsuba's OBJ reader turns v upside down (its flip_tex_coords), so that row 0 of an image is at v = 1.
    s.texcoords.emplace_back(u, 1.f - v);
}

/// An OBJ index (1-based, negative = relative to the count so far, 0 = absent) as 0-based, or -1
/// when absent; an error for one outside [1, count].
int64_t resolve(ObjState &s, int raw, size_t count, const char *what) {
    if (raw == 0) return -1;
    const int64_t index = raw > 0 ? int64_t(raw) - 1 : int64_t(count) + raw;
    if ((index < 0 || index >= int64_t(count)) && s.error.empty())
        s.error = "face " + std::to_string(s.faceCount) + ": " + what + " index " + std::to_string(raw) +
                  " out of range (the file defines " + std::to_string(count) + " before it)";
    return index;
}

void onFace(void *user, tinyobj::index_t *corners, int count) {
    auto &s = *static_cast<ObjState *>(user);
    ++s.faceCount;
    if (!s.error.empty()) return;
    if (count < 3) {
        s.error = "face " + std::to_string(s.faceCount) + " has " + std::to_string(count) +
                  " vertices; a face needs at least 3";
        return;
    }
    uint32_t first = 0, previous = 0;
    for (int k = 0; k < count; ++k) {
        const tinyobj::index_t &c = corners[k];
        if (c.vertex_index == 0) s.error = "face " + std::to_string(s.faceCount) + ": a corner has no vertex index";
        const Corner key{resolve(s, c.vertex_index, s.positions.size(), "vertex"),
                         resolve(s, c.texcoord_index, s.texcoordCount, "texcoord"),
                         resolve(s, c.normal_index, s.normals.size(), "normal")};
        if (!s.error.empty()) return;
        s.everyCornerHasNormal &= key.vn >= 0;
        s.everyCornerHasTexcoord &= key.vt >= 0;
        const auto [it, isNew] = s.vertexOf.try_emplace(key, uint32_t(s.vertices.size()));
        if (isNew) s.vertices.push_back(key);
        if (s.vertices.size() > kMaxVertices) s.error = "more than 2^28 distinct face corners";
        if (k == 0) first = it->second;
        if (k >= 2) s.indices.insert(s.indices.end(), {first, previous, it->second});
        previous = it->second;
    }
}

}  // namespace

Mesh readObj(const std::string &path, std::string_view bytes) {
    ObjState state;
    tinyobj::callback_t callbacks;
    callbacks.vertex_cb = onVertex;
    callbacks.normal_cb = onNormal;
    callbacks.texcoord_cb = onTexcoord;
    callbacks.index_cb = onFace;
    MemoryBuffer buffer(bytes);
    std::istream stream(&buffer);
    std::string warning, error;
    // No material reader: materials do not matter here, and an mtllib line must not open files.
    const bool ok = tinyobj::LoadObjWithCallback(stream, callbacks, &state, nullptr, &warning, &error);
    if (!state.error.empty()) throw SceneError(path, 0, state.error);
    if (!ok || !error.empty()) throw SceneError(path, 0, "cannot read OBJ: " + error);
    Mesh mesh;
    mesh.positions.reserve(state.vertices.size());
    for (const Corner &c : state.vertices) mesh.positions.push_back(state.positions[size_t(c.v)]);
    if (state.everyCornerHasNormal && !state.vertices.empty()) {
        mesh.normals.reserve(state.vertices.size());
        for (const Corner &c : state.vertices) mesh.normals.push_back(state.normals[size_t(c.vn)]);
    }
    if (state.everyCornerHasTexcoord && !state.vertices.empty()) {
        mesh.texcoords.reserve(state.vertices.size());
        for (const Corner &c : state.vertices) mesh.texcoords.push_back(state.texcoords[size_t(c.vt)]);
    }
    mesh.indices = std::move(state.indices);
    return mesh;
}

}  // namespace mcval
