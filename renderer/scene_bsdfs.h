// Mitsuba's conductor, roughconductor, dielectric, roughdielectric, plastic and roughplastic as a scene file
// gives them: the BSDFs of the BSDF checks, their parameters constants with Mitsuba's defaults.
#pragma once

#include <string>

#include "load_state.h"
#include "xml_props.h"

namespace mcval {

/// What a <texture> or a <ref> (to a texture) inside a <bsdf> gives its property: "a bitmap texture", "a reference
/// to \"t\" (a texture)"; "" for any other element.
std::string textureGiven(const XmlContext &ctx, const pugi::xml_node &child);

/// Whether a <bsdf type> is one of them.
bool isScatteringBsdf(const std::string &type);

/// The material of such a <bsdf>; nullptr where a parameter is given in a form this renderer does not read (a
/// texture, a per-wavelength spectrum, an index that differs by channel, a named conductor, anisotropic
/// roughness), which `unread` then names with its line. A malformed parameter is an error, as in Mitsuba.
Material readScatteringBsdf(const XmlContext &ctx, const pugi::xml_node &node, std::string &unread);

}  // namespace mcval
