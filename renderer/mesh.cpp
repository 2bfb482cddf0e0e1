#include "mesh.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error.h"
#include "obj_reader.h"
#include "ply_reader.h"
#include "serialized_reader.h"

namespace mcval {

namespace {

namespace fs = std::filesystem;

constexpr uint64_t kMaxMeshFileBytes = uint64_t(2) << 30;  // 2 GiB: far above any scene's mesh

/// What a path that is not a regular file is, for the message.
const char *kindOf(fs::file_type type) {
    switch (type) {
    case fs::file_type::not_found: return "not found";
    case fs::file_type::directory: return "is a directory";
    case fs::file_type::fifo: return "is a FIFO";
    case fs::file_type::socket: return "is a socket";
    case fs::file_type::block:
    case fs::file_type::character: return "is a device";
    default: return "is not a regular file";
    }
}

/// Closes a file descriptor on every path out.
struct FdGuard {
    int fd;
    ~FdGuard() {
        if (fd >= 0) ::close(fd);
    }
};

/// The whole content of a regular file (a symlink to one is fine). Anything else is refused
/// before it is opened, so a FIFO or a device can never block the reader.
std::string readRegularFile(const std::string &path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);  // follows symlinks; no exception on a bad path
    if (ec && status.type() != fs::file_type::not_found)
        throw SceneError(path, 0, "cannot read mesh file: " + ec.message());
    if (status.type() != fs::file_type::regular) throw SceneError(path, 0, std::string("mesh file ") + kindOf(status.type()));
    // O_NONBLOCK and fstat on the open file: the path may have been swapped for a FIFO since status().
    const FdGuard file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) throw SceneError(path, 0, std::string("cannot open mesh file: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(file.fd, &st) != 0 || !S_ISREG(st.st_mode)) throw SceneError(path, 0, "mesh file is not a regular file");
    if (uint64_t(st.st_size) > kMaxMeshFileBytes)
        throw SceneError(path, 0, "mesh file has " + std::to_string(st.st_size) + " bytes; at most 2 GiB are supported");
    std::string bytes(size_t(st.st_size), '\0');
    size_t done = 0;
    while (done < bytes.size()) {  // a file that shrinks meanwhile ends early; one that grows is cut
        const ssize_t n = ::read(file.fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) throw SceneError(path, 0, std::string("cannot read mesh file: ") + std::strerror(errno));
        if (n == 0) break;
        done += size_t(n);
    }
    bytes.resize(done);
    return bytes;
}

/// True if path ends with ext, ignoring case.
bool hasExtension(const std::string &path, const std::string &ext) {
    if (path.size() < ext.size()) return false;
    for (size_t i = 0; i < ext.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(path[path.size() - ext.size() + i])) != ext[i]) return false;
    return true;
}

/// A file's triangles in world space: the file's normals (unless faceNormals) or Mitsuba's vertex normals
/// (unless faceNormals: then flat).
Mesh placed(Mesh mesh, const Transform &toWorld, bool faceNormals) {
    if (faceNormals) mesh.normals.clear();
    const bool fileHasNormals = !mesh.normals.empty();
    mesh = transformMesh(std::move(mesh), toWorld);
    if (!fileHasNormals && !faceNormals) computeVertexNormals(mesh);
    return mesh;
}

/// A quad (a, b, c, d counter-clockwise seen from the front) as two triangles.
void addQuad(Mesh &m, const Vec3f &a, const Vec3f &b, const Vec3f &c, const Vec3f &d) {
    const auto base = static_cast<uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c, d});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base + 2, base + 3, base});
}

}  // namespace

Mesh makeRectangle(const Transform &toWorld) {
    Mesh m;
    addQuad(m, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0});
    // Mitsuba's rectangle: (u, v) = ((x + 1) / 2, (y + 1) / 2), which the triangles interpolate exactly.
    m.texcoords = {{0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f}, {0.f, 1.f}};
    return transformMesh(std::move(m), toWorld);
}

Mesh makeCube(const Transform &toWorld) {
    Mesh m;
    for (int axis = 0; axis < 3; ++axis) {
        for (float s : {-1.f, 1.f}) {
            // Tangents u, v with u x v = s * e_axis, so the quad faces outward.
            float n[3] = {0, 0, 0}, u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
            n[axis] = s;
            u[(axis + 1) % 3] = 1.f;
            v[(axis + 2) % 3] = s;
            const auto corner = [&](float a, float b) {
                return Vec3f(n[0] + a * u[0] + b * v[0], n[1] + a * u[1] + b * v[1], n[2] + a * u[2] + b * v[2]);
            };
            addQuad(m, corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1));
        }
    }
    return transformMesh(std::move(m), toWorld);
}

Mesh loadMeshFile(const std::string &path, const Transform &toWorld, bool faceNormals) {
    // Vertices as Mitsuba has them: a PLY's own list; for an OBJ, one per distinct corner. This
    // decides the vertex normals.
    const std::string bytes = readRegularFile(path);
    // The extension decides; a file named otherwise is a PLY if it starts like one.
    const bool isObj = hasExtension(path, ".obj");
    const bool isPly = hasExtension(path, ".ply") || (!isObj && bytes.compare(0, 3, "ply") == 0);
    if (!isObj && !isPly) throw SceneError(path, 0, "unknown mesh format: expected a .obj file or a PLY file");
    Mesh mesh = isObj ? readObj(path, bytes) : readPly(path, bytes);
    if (mesh.indices.empty()) throw SceneError(path, 0, "mesh has no triangles");
    return placed(std::move(mesh), toWorld, faceNormals);
}

Mesh loadSerializedFile(const std::string &path, uint32_t shapeIndex, const Transform &toWorld, bool faceNormals,
                        bool flipNormals) {
    Mesh mesh = placed(readSerialized(path, readRegularFile(path), shapeIndex), toWorld, faceNormals);
    // Mitsuba negates both normals; with one-sided surfaces that is the winding reversed as well.
    if (flipNormals) {
        for (Vec3f &n : mesh.normals) n = -n;
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    }
    return mesh;
}

Mesh transformMesh(Mesh mesh, const Transform &toWorld) {
    for (Vec3f &p : mesh.positions) p = toWorld.point(p);
    for (Vec3f &n : mesh.normals) n = normalize(toWorld.normal(n));
    if (toWorld.determinant3() < 0.f)
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    return mesh;
}

void computeVertexNormals(Mesh &mesh) {
    MCR_ASSERT(mesh.indices.size() % 3 == 0);
    std::vector<Vec3f> sum(mesh.positions.size());
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t idx[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
        // The readers check every index; a bad one here is a bug, not bad input.
        MCR_ASSERT(idx[0] < mesh.positions.size() && idx[1] < mesh.positions.size() && idx[2] < mesh.positions.size());
        const Vec3f v[3] = {mesh.positions[idx[0]], mesh.positions[idx[1]], mesh.positions[idx[2]]};
        Vec3f n = cross(v[1] - v[0], v[2] - v[0]);
        const float len2 = squaredNorm(n);
        if (!(len2 > 0.f)) continue;  // degenerate triangle: no direction to contribute
        n = n / std::sqrt(len2);
        for (int j = 0; j < 3; ++j) {
            const Vec3f d0 = v[(j + 1) % 3] - v[j], d1 = v[(j + 2) % 3] - v[j];
            const float l0 = squaredNorm(d0), l1 = squaredNorm(d1);
            if (!(l0 > 0.f && l1 > 0.f)) continue;
            const float c = std::max(-1.f, std::min(1.f, dot(d0, d1) / std::sqrt(l0 * l1)));
            sum[idx[j]] = sum[idx[j]] + n * std::acos(c);
        }
    }
    mesh.normals.resize(mesh.positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const float len2 = squaredNorm(sum[i]);
        // An isolated vertex keeps an arbitrary unit normal; no triangle will interpolate it.
        mesh.normals[i] = len2 > 0.f ? sum[i] / std::sqrt(len2) : Vec3f(0.f, 0.f, 1.f);
    }
}

}  // namespace mcval
