// OBJ meshes through tinyobjloader, with every index and value it gives back checked.
#pragma once

#include <string>
#include <string_view>

#include "scene.h"

namespace mcval {

/// The triangles of an OBJ file: one vertex per distinct (position, texcoord, normal) index
/// tuple in order of first use, polygons split into fans (0, k-1, k), normals only if every
/// corner has one. `path` only names the file in errors; mtllib lines are ignored. Throws SceneError.
Mesh readObj(const std::string &path, std::string_view bytes);

}  // namespace mcval
