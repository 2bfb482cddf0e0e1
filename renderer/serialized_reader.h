// Mitsuba's .serialized meshes (zlib-compressed binary), read as Mitsuba 3.9 reads them: every count,
// offset and index is checked, so a damaged file gives a SceneError instead of a crash or a huge allocation.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "scene.h"

namespace mcval {

/// The triangles of shape `shapeIndex` of a .serialized file (format versions 3 and 4), in the file's
/// own vertex order, with the file's vertex normals if it has them; texture coordinates and colours
/// are read past. `path` only names the file in errors. Throws SceneError.
Mesh readSerialized(const std::string &path, std::string_view bytes, uint32_t shapeIndex);

}  // namespace mcval
