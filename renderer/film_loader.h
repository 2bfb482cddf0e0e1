// Reading a sensor's <film> element (scene_loader.cpp reads the rest of the sensor).
#pragma once

#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// Reads <film type="hdrfilm"> and its <rfilter> into `film`; throws SceneError at the offending line.
void loadFilm(const XmlContext &ctx, const pugi::xml_node &node, FilmSpec &film);

}  // namespace mcval
