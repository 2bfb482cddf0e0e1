// A strict PLY reader for triangle meshes: every count, type, index and value is checked, so a
// damaged file gives a SceneError instead of a crash, a hang or a huge allocation.
#pragma once

#include <string>
#include <string_view>

#include "scene.h"

namespace mcval {

/// The triangles of a PLY file (ascii, binary little or big endian) in the file's own vertex
/// order, with the file's normals if it has nx, ny, nz; polygons are split into fans
/// (0, k-1, k). `path` only names the file in errors. Throws SceneError.
Mesh readPly(const std::string &path, std::string_view bytes);

}  // namespace mcval
