// A scene's files: reading one, and following <path> and <include> as Mitsuba 3 does.
#pragma once

#include <string>
#include <vector>

#include <pugixml.hpp>

#include "xml_props.h"

namespace mcval {

/// Includes deeper than this are a cycle or a mistake.
constexpr size_t kMaxIncludeDepth = 16;

/// The whole file, refusing what is not a regular file (a FIFO would block) or is too large.
std::string readSceneFile(const std::string &path);

/// `text` (the file `path`) parsed into `doc`; SceneError naming the file and line of malformed XML.
void parseSceneText(pugi::xml_document &doc, const std::string &text, const std::string &path);

/// A <path value="...">: its folder, relative to the file that says it, is searched first from now on.
void addPath(XmlContext &ctx, const pugi::xml_node &node);

/// An <include filename="...">: the included file's <scene>, read, kept in `ctx` (its nodes keep their file
/// and line) and returned. `chain`: the files that include it, outermost first, to refuse a cycle; the
/// included file is appended to it.
pugi::xml_node includeFile(XmlContext &ctx, const pugi::xml_node &node, std::vector<std::string> &chain);

}  // namespace mcval
