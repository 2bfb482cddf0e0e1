#include "mesh.h"

#include <cmath>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "error.h"

namespace mcr {

namespace {

/// Applies toWorld; a mirroring transform gets its winding reversed so the front side stays
/// where the transformed normal points (as Mitsuba's analytic shapes do).
Mesh transformed(Mesh mesh, const Transform &toWorld) {
    for (Vec3f &p : mesh.positions) p = toWorld.point(p);
    for (Vec3f &n : mesh.normals) n = normalize(toWorld.normal(n));
    if (toWorld.determinant3() < 0.f)
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
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
    return transformed(std::move(m), toWorld);
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
    return transformed(std::move(m), toWorld);
}

Mesh loadMeshFile(const std::string &path, const Transform &toWorld, bool faceNormals) {
    Assimp::Importer importer;
    // Vertices as Mitsuba has them: a PLY's own list; for an OBJ, one per distinct corner (Assimp
    // gives one per face corner, so join the identical ones). This decides the vertex normals.
    const bool isObj = path.size() >= 4 && (path.compare(path.size() - 4, 4, ".obj") == 0 ||
                                            path.compare(path.size() - 4, 4, ".OBJ") == 0);
    const unsigned flags = aiProcess_Triangulate | (isObj ? aiProcess_JoinIdenticalVertices : 0u);
    const aiScene *scene = importer.ReadFile(path, flags);
    if (!scene || !scene->mRootNode) throw SceneError(path, 0, std::string("cannot read mesh: ") + importer.GetErrorString());
    Mesh mesh;
    bool allHaveNormals = true;
    for (unsigned k = 0; k < scene->mNumMeshes; ++k) allHaveNormals &= scene->mMeshes[k]->HasNormals();
    for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
        const aiMesh *am = scene->mMeshes[k];
        const auto base = static_cast<uint32_t>(mesh.positions.size());
        for (unsigned i = 0; i < am->mNumVertices; ++i) {
            const aiVector3D &p = am->mVertices[i];
            mesh.positions.emplace_back(p.x, p.y, p.z);
            if (allHaveNormals && !faceNormals) {
                const aiVector3D &n = am->mNormals[i];
                mesh.normals.emplace_back(n.x, n.y, n.z);
            }
        }
        for (unsigned f = 0; f < am->mNumFaces; ++f) {
            const aiFace &face = am->mFaces[f];
            if (face.mNumIndices != 3) continue;  // points and lines carry no surface
            for (int j = 0; j < 3; ++j) mesh.indices.push_back(base + face.mIndices[j]);
        }
    }
    if (mesh.indices.empty()) throw SceneError(path, 0, "mesh has no triangles");
    mesh = transformed(std::move(mesh), toWorld);
    if (!allHaveNormals && !faceNormals) computeVertexNormals(mesh);
    return mesh;
}

void computeVertexNormals(Mesh &mesh) {
    std::vector<Vec3f> sum(mesh.positions.size());
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const uint32_t idx[3] = {mesh.indices[i], mesh.indices[i + 1], mesh.indices[i + 2]};
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

}  // namespace mcr
