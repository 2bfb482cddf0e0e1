// A scene file's <emitter> elements: the top-level ones and a shape's area emitter.
#pragma once

#include <string>
#include <vector>

#include "load_state.h"
#include "xml_props.h"

namespace mcval {

/// Reads a point light into scene.pointLights or a constant emitter into scene.environment; spot and
/// directional lights, and the types this renderer does not model (projector, envmap), go to
/// deferred.otherEmitters, to be judged once the integrator is known; any other type fails at its line.
void loadEmitter(const XmlContext &ctx, const pugi::xml_node &node, SceneDescription &scene, Deferred &deferred);

/// The radiance of a shape's <emitter type="area"> (Mitsuba's `radiance`, default 1).
Color readAreaRadiance(const XmlContext &ctx, const pugi::xml_node &node);

/// The deferred top-level emitters, now that `chosen` is known to read `reads`: a spot or directional light
/// it reads is read into the scene, an unmodelled one it would read is refused at its line, and every other
/// one is added to `skipped` (the note's entries).
void judgeOtherEmitters(const XmlContext &ctx, const Deferred &deferred, const std::string &chosen,
                        SceneDescription &scene, std::vector<std::string> &skipped);

}  // namespace mcval
