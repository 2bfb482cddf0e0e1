// Mitsuba's <sensor type="perspective"> and <sensor type="orthographic">, with their <film> and <sampler>.
#pragma once

#include "load_state.h"
#include "scene.h"
#include "xml_props.h"

namespace mcval {

/// Reads the sensor at `node` into scene.camera, scene.film and the sampler fields (its medium, inline or by
/// <ref>, into deferred.media); throws SceneError naming file and line for what it cannot model.
void loadSensor(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred);

}  // namespace mcval
