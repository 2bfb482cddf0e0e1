// <path> and <include> as Mitsuba 3 follows them: a <path> folder is searched before the scene's own (the
// newest first), an <include> brings its file's elements in where it stands (its errors name that file and
// line), and a missing file, a missing folder, a cycle and an included file that is no <scene> are refused.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "error.h"
#include "scene.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

/// A fresh folder under the temporary directory.
fs::path folder(const std::string &name) {
    const fs::path dir = fs::temp_directory_path() / ("mcval_files_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void write(const fs::path &path, const std::string &text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

const std::string kSensor =
    "<sensor type=\"perspective\"><float name=\"fov\" value=\"40\"/><film type=\"hdrfilm\"><integer name=\"width\" "
    "value=\"8\"/><integer name=\"height\" value=\"8\"/></film></sensor>\n";

/// A triangle whose first vertex is at x = `x`: which file was read shows in the mesh.
std::string triangle(float x) {
    return "v " + std::to_string(x) + " 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
}

std::string errorOf(const fs::path &scene) {
    try {
        loadScene(scene.string());
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneFiles, APathFolderIsSearchedBeforeTheScenesOwnTheNewestFirst) {
    const fs::path dir = folder("path");
    write(dir / "scenes" / "tri.obj", triangle(5));
    write(dir / "common" / "tri.obj", triangle(7));
    write(dir / "newer" / "tri.obj", triangle(9));
    const std::string shape = "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/></shape>\n";
    write(dir / "scenes" / "own.xml", "<scene version=\"3.0.0\">\n" + kSensor + shape + "</scene>\n");
    write(dir / "scenes" / "one.xml",
          "<scene version=\"3.0.0\">\n<path value=\"../common\"/>\n" + kSensor + shape + "</scene>\n");
    write(dir / "scenes" / "two.xml", "<scene version=\"3.0.0\">\n<path value=\"../common\"/>\n<path value=\"../newer\"/>\n" +
                                          kSensor + shape + "</scene>\n");
    EXPECT_FLOAT_EQ(loadScene((dir / "scenes" / "own.xml").string()).meshes[0].positions[0].x, 5.f);
    EXPECT_FLOAT_EQ(loadScene((dir / "scenes" / "one.xml").string()).meshes[0].positions[0].x, 7.f);
    EXPECT_FLOAT_EQ(loadScene((dir / "scenes" / "two.xml").string()).meshes[0].positions[0].x, 9.f);
}

TEST(SceneFiles, AnIncludeBringsItsElementsInAndItsErrorsNameItsFileAndLine) {
    const fs::path dir = folder("include");
    write(dir / "parts" / "shapes.xml", "<scene version=\"3.0.0\">\n<default name=\"r\" value=\"0.25\"/>\n"
                                        "<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>\n"
                                        "<shape type=\"cube\"/>\n</scene>\n");
    write(dir / "main.xml", "<scene version=\"3.0.0\">\n" + kSensor + "<include filename=\"parts/shapes.xml\"/>\n</scene>\n");
    const SceneDescription scene = loadScene((dir / "main.xml").string());
    ASSERT_EQ(scene.spheres.size(), 1u);
    EXPECT_FLOAT_EQ(scene.spheres[0].radius, 0.25f);  // the included file's <default>
    EXPECT_EQ(scene.meshes.size(), 1u);
    write(dir / "parts" / "bad.xml", "<scene version=\"3.0.0\">\n\n<shape type=\"teapot\"/>\n</scene>\n");
    write(dir / "bad_main.xml", "<scene version=\"3.0.0\">\n" + kSensor + "<include filename=\"parts/bad.xml\"/>\n</scene>\n");
    const std::string error = errorOf(dir / "bad_main.xml");
    EXPECT_NE(error.find((dir / "parts" / "bad.xml").string() + ":3:"), std::string::npos) << error;
    EXPECT_NE(error.find("teapot"), std::string::npos) << error;
}

TEST(SceneFiles, WhatCannotBeFollowedIsRefusedOnItsLine) {
    const fs::path dir = folder("refused");
    const auto scene = [&](const std::string &name, const std::string &body) {
        write(dir / (name + ".xml"), "<scene version=\"3.0.0\">\n" + kSensor + body + "\n</scene>\n");
        return errorOf(dir / (name + ".xml"));
    };
    const std::string missing = scene("missing", "<include filename=\"nope.xml\"/>");
    EXPECT_NE(missing.find("missing.xml:3: <include>: no such file: nope.xml (looked in"), std::string::npos) << missing;
    EXPECT_NE(scene("nofolder", "<path value=\"no/such/folder\"/>").find("nofolder.xml:3: <path>: no such folder"),
              std::string::npos);
    const std::string cycle = scene("cycle", "<include filename=\"cycle.xml\"/>");
    EXPECT_NE(cycle.find("includes itself"), std::string::npos) << cycle;
    write(dir / "notscene.xml", "<shape type=\"cube\"/>\n");
    EXPECT_NE(scene("notscene_main", "<include filename=\"notscene.xml\"/>").find("root must be <scene>"),
              std::string::npos);
    write(dir / "broken.xml", "<scene version=\"3.0.0\">\n<shape type=\"cube\">\n");
    const std::string broken = scene("broken_main", "<include filename=\"broken.xml\"/>");
    EXPECT_NE(broken.find("broken.xml:"), std::string::npos) << broken;
    EXPECT_NE(broken.find("malformed XML"), std::string::npos) << broken;
}
