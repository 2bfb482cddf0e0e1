// Triangle meshes: read from PLY, OBJ or Mitsuba's serialized files, or Mitsuba's built-in rectangle and cube.
#pragma once

#include <cstdint>
#include <string>

#include "scene.h"
#include "transform.h"

namespace mcval {

/// Mitsuba's `rectangle`: [-1,1]^2 in the z = 0 plane, front side +z, flat.
Mesh makeRectangle(const Transform &toWorld);

/// Mitsuba's `cube`: [-1,1]^3, front sides outward, flat.
Mesh makeCube(const Transform &toWorld);

/// An OBJ or PLY file, transformed to world space. Without normals in the file (or with
/// faceNormals) shading is smooth with Mitsuba's vertex normals (or flat). Throws SceneError.
Mesh loadMeshFile(const std::string &path, const Transform &toWorld, bool faceNormals);

/// Shape `shapeIndex` of a Mitsuba .serialized file, transformed and given normals as loadMeshFile's
/// meshes are; flipNormals turns it inside out (Mitsuba's flip_normals). Throws SceneError.
Mesh loadSerializedFile(const std::string &path, uint32_t shapeIndex, const Transform &toWorld, bool faceNormals,
                        bool flipNormals);

/// The mesh under toWorld; a mirroring transform reverses the winding so the front side stays where
/// the transformed normals point. Applying two in turn equals applying their product.
Mesh transformMesh(Mesh mesh, const Transform &toWorld);

/// Vertex normals as Mitsuba computes them: face normals weighted by the angle at each vertex
/// (Thuermer and Wuethrich 1998).
void computeVertexNormals(Mesh &mesh);

}  // namespace mcval
