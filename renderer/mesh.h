// Triangle meshes: read from PLY or OBJ files, or Mitsuba's built-in rectangle and cube.
#pragma once

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

/// Vertex normals as Mitsuba computes them: face normals weighted by the angle at each vertex
/// (Thuermer and Wuethrich 1998).
void computeVertexNormals(Mesh &mesh);

}  // namespace mcval
