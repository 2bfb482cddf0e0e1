#include "scene_files.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "error.h"
#include "scene_limits.h"

namespace mcval {

namespace fs = std::filesystem;

std::string readSceneFile(const std::string &path) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec) throw SceneError(path, 0, "cannot open scene file: " + ec.message());
    if (!fs::is_regular_file(status)) throw SceneError(path, 0, "not a regular file");
    const auto size = fs::file_size(path, ec);
    if (ec || size > static_cast<uintmax_t>(kMaxSceneFileBytes))
        throw SceneError(path, 0, "scene file larger than " + std::to_string(kMaxSceneFileBytes >> 20) + " MiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(path, 0, "cannot open scene file");
    std::stringstream buf;
    buf << in.rdbuf();
    return buf.str();
}

void parseSceneText(pugi::xml_document &doc, const std::string &text, const std::string &path) {
    const pugi::xml_parse_result parsed = doc.load_buffer(text.data(), text.size());
    if (!parsed) {
        const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + parsed.offset, '\n'));
        throw SceneError(path, line, std::string("malformed XML: ") + parsed.description());
    }
}

void addPath(XmlContext &ctx, const pugi::xml_node &node) {
    const std::string value = ctx.attr(node, "value");
    if (value.empty()) ctx.fail(node, "expected value=\"a folder\"");
    fs::path folder(value);
    if (folder.is_relative()) folder = fs::path(ctx.fileOf(node)).parent_path() / folder;
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) ctx.fail(node, "no such folder (" + folder.string() + ")");
    ctx.folders.insert(ctx.folders.begin(), folder.string());
}

pugi::xml_node includeFile(XmlContext &ctx, const pugi::xml_node &node, std::vector<std::string> &chain) {
    const std::string name = ctx.attr(node, "filename");
    if (name.empty()) ctx.fail(node, "expected filename=\"a scene file\"");
    const std::string found = ctx.resolve(name);
    std::error_code ec;
    if (!fs::is_regular_file(found, ec)) {
        std::string searched;
        for (const std::string &f : ctx.folders) searched += (searched.empty() ? "" : ", ") + f;
        ctx.fail(node, "no such file: " + name + " (looked in " + searched + ")");
    }
    const std::string canonical = fs::weakly_canonical(found, ec).string();
    if (std::find(chain.begin(), chain.end(), canonical) != chain.end() || chain.size() >= kMaxIncludeDepth)
        ctx.fail(node, "the file includes itself (" + canonical + ")");
    chain.push_back(canonical);
    XmlContext::Included &inc = ctx.included.emplace_back();
    inc.file = found;
    inc.text = readSceneFile(found);
    parseSceneText(inc.doc, inc.text, found);
    const pugi::xml_node root = inc.doc.document_element();
    if (std::string(root.name()) != "scene") ctx.fail(root, "an included file's root must be <scene>");
    return root;
}

}  // namespace mcval
