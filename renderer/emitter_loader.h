// A scene file's top-level <emitter> elements.
#pragma once

#include "load_state.h"
#include "xml_props.h"

namespace mcval {

/// Reads a point light into scene.pointLights or a constant emitter into scene.environment; a type no
/// integrator of ours uses (directional, spot, projector, envmap) goes to deferred.otherEmitters, to be
/// skipped with a note; any other type fails at its line.
void loadEmitter(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred);

}  // namespace mcval
