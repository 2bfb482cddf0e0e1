// A shape's <bsdf>: Mitsuba's diffuse, the scattering BSDFs of scene_bsdfs.h, a twosided around them, and <ref>s
// to bsdfs anywhere in the file.
#pragma once

#include "load_state.h"
#include "xml_props.h"

namespace mcval {

/// Deepest nesting of bsdfs (a twosided in a twosided ...) and of references through them: deeper is a
/// mistake, refused with its line before it costs stack.
constexpr int kMaxBsdfDepth = 64;

/// Notes every <bsdf id> at or under `node` in defs.bsdfNodes, so that a <ref> before it finds it; an id
/// given twice fails, as in Mitsuba.
void registerBsdfs(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs);

/// A <bsdf>'s material (one with an id is read once and remembered in defs). A type this renderer does not
/// model, or one with a parameter it cannot read, is deferred: only some integrators can ignore it. `depth`: the
/// bsdfs and references around it.
Material loadBsdf(const XmlContext &ctx, const pugi::xml_node &node, Definitions &defs, Deferred &deferred,
                  int depth = 0);

/// The material of the bsdf a <ref id> names, wherever in the file it is defined; `depth`: the named bsdf's, as
/// if it stood where the reference does.
Material resolveBsdfRef(const XmlContext &ctx, const pugi::xml_node &ref, Definitions &defs, Deferred &deferred,
                        int depth = 0);

}  // namespace mcval
