// <shape type="shapegroup"> and <shape type="instance">: a group's shapes appear only where instances
// place them, under the instance's to_world after their own; what Mitsuba refuses is refused here.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "bsdf_albedo.h"

#include "embree_scene.h"
#include "error.h"
#include "scene.h"
#include "shapegroup_loader.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

std::string writeScene(const std::string &name, const std::string &shapes) {
    const fs::path path = fs::temp_directory_path() /
                          ("mcval_shapegroup_" + std::to_string(::getpid()) + "_" + name + ".xml");
    std::ofstream(path) << "<scene version=\"3.0.0\">\n  <sensor type=\"perspective\"><float name=\"fov\" "
                           "value=\"40\"/></sensor>\n"
                        << shapes << "</scene>\n";
    return path.string();
}

/// The scene, its file removed once read.
SceneDescription load(const std::string &name, const std::string &shapes) {
    const std::string path = writeScene(name, shapes);
    SceneDescription scene = loadScene(path);
    fs::remove(path);
    return scene;
}

/// The SceneError message of loading the shapes, or "" if they load.
std::string errorOf(const std::string &name, const std::string &shapes) {
    const std::string path = writeScene(name, shapes);
    std::string message;
    try {
        loadScene(path);
    } catch (const SceneError &e) {
        message = e.what();
    }
    fs::remove(path);
    return message;
}

/// The first hit of the ray o + t d, which must exist.
Hit trace(const SceneDescription &scene, const Vec3f &o, const Vec3f &d) {
    const EmbreeScene embree(scene.meshes, scene.spheres, scene.disks, scene.cylinders, scene.bsdfs);
    Ray ray;
    ray.o = o;
    ray.d = d;
    Hit hit;
    EXPECT_TRUE(embree.intersect(ray, hit));
    return hit;
}

// A rectangle lifted to z = 1 by its own to_world, and a unit sphere at (4, 0, 0).
const std::string kGroup = R"(  <shape type="shapegroup" id="g">
    <shape type="rectangle"><transform name="to_world"><translate value="0, 0, 1"/></transform>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.25"/></bsdf></shape>
    <shape type="sphere"><point name="center" value="4, 0, 0"/></shape>
  </shape>
)";

std::string instance(const std::string &transform) {
    return "  <shape type=\"instance\"><ref id=\"g\"/><transform name=\"to_world\">" + transform +
           "</transform></shape>\n";
}

}  // namespace

TEST(ShapeGroup, IsRenderedOnlyThroughItsInstances) {
    EXPECT_NE(errorOf("alone", kGroup).find("the scene has no <shape>"), std::string::npos);
    const SceneDescription scene =
        load("two", kGroup + instance("<translate value=\"0, 10, 0\"/>") + instance("<translate value=\"0, 20, 0\"/>"));
    ASSERT_EQ(scene.meshes.size(), 2u);
    ASSERT_EQ(scene.spheres.size(), 2u);
    EXPECT_FLOAT_EQ(test::frontAlbedo(scene, scene.meshes[1]).x, 0.25f);  // a member keeps its bsdf
    EXPECT_FLOAT_EQ(scene.spheres[1].center.y, 20.f);
    EXPECT_NE(scene.meshes[0].name.find("instance at line"), std::string::npos);
    // An instance may come before its shapegroup, as Mitsuba resolves references once the file is read;
    // a shapegroup without an id is read and not rendered, as in Mitsuba.
    const SceneDescription before = load("before", instance("<translate value=\"0, 3, 0\"/>") + kGroup +
                                                       "<shape type=\"shapegroup\"><shape type=\"cube\"/></shape>\n");
    ASSERT_EQ(before.spheres.size(), 1u);
    EXPECT_EQ(before.meshes.size(), 1u);
    EXPECT_FLOAT_EQ(before.spheres[0].center.y, 3.f);
}

TEST(ShapeGroup, AnInstancesToWorldIsAppliedAfterTheMembersOwn) {
    // Rotated 90 degrees about y: the member's z = 1 goes to x = 1, its +z normal to +x. Composed in the
    // other order (the rotation first, then the lift) the rectangle would lie at z = 1, facing +x.
    const SceneDescription scene = load("composed", kGroup + instance("<rotate y=\"1\" angle=\"90\"/>"));
    const Hit hit = trace(scene, {5.f, 0.2f, 0.3f}, {-1.f, 0.f, 0.f});
    EXPECT_NEAR(hit.t, 4.f, 1e-5f);
    EXPECT_NEAR(hit.ng.x, 1.f, 1e-6f);
    EXPECT_NEAR(hit.ns.x, 1.f, 1e-6f);
    // The sphere's centre (4, 0, 0) turned to (0, 0, -4): hit from below at (0, -1, -4).
    const Hit below = trace(scene, {0.f, -5.f, -4.f}, {0.f, 1.f, 0.f});
    EXPECT_NEAR(below.t, 4.f, 1e-4f);
    EXPECT_NEAR(below.ng.y, -1.f, 1e-5f);
}

TEST(ShapeGroup, AMirroringInstanceKeepsFrontSidesOut) {
    // As in Mitsuba, which transforms an instance's normals with its surface: the mirrored sphere's
    // normal still points out, the mirrored rectangle still faces +z.
    const SceneDescription scene = load("mirror", kGroup + instance("<scale value=\"-2, 2, 2\"/>"));
    EXPECT_FALSE(scene.spheres[0].flipNormals);
    EXPECT_FLOAT_EQ(scene.spheres[0].center.x, -8.f);
    EXPECT_FLOAT_EQ(scene.spheres[0].radius, 2.f);
    const Hit hit = trace(scene, {0.5f, 0.5f, 5.f}, {0.f, 0.f, -1.f});
    EXPECT_NEAR(hit.t, 3.f, 1e-5f);
    EXPECT_NEAR(hit.ng.z, 1.f, 1e-6f);
}

TEST(ShapeGroup, DisksAndCylindersTakeTheInstancesToWorldAfterTheirOwn) {
    // Mitsuba's values (ray_intersect on the same instances): a cylinder of radius 0.5 under scale 2 then a
    // lift by 1 is hit at x = 1, z = 2 from (5, 0, 2); mirrored in x, its normal still points out; a
    // mirror in z turns a disk's normal, and flip_normals survives an instance.
    const std::string group = R"(  <shape type="shapegroup" id="c"><shape type="cylinder"><float name="radius" value="0.5"/>
    </shape></shape>
  <shape type="shapegroup" id="d"><shape type="disk"><boolean name="flip_normals" value="true"/></shape></shape>
)";
    const auto placed = [&](const std::string &id, const std::string &transform) {
        return group + "  <shape type=\"instance\"><ref id=\"" + id + "\"/><transform name=\"to_world\">" + transform +
               "</transform></shape>\n";
    };
    Hit hit = trace(load("cyl", placed("c", "<scale value=\"2\"/><translate value=\"0, 0, 1\"/>")), {5.f, 0.f, 2.f},
                    {-1.f, 0.f, 0.f});
    EXPECT_NEAR(hit.t, 4.f, 1e-5f);
    EXPECT_NEAR(hit.ng.x, 1.f, 1e-6f);
    hit = trace(load("cyl_mirror", placed("c", "<scale value=\"-2, 2, 2\"/>")), {5.f, 0.f, 0.5f}, {-1.f, 0.f, 0.f});
    EXPECT_NEAR(hit.t, 4.f, 1e-5f);
    EXPECT_NEAR(hit.ng.x, 1.f, 1e-6f);
    hit = trace(load("disk", placed("d", "<translate value=\"0, 0, 1\"/>")), {0.3f, 0.2f, 5.f}, {0.f, 0.f, -1.f});
    EXPECT_NEAR(hit.t, 4.f, 1e-5f);
    EXPECT_NEAR(hit.ng.z, -1.f, 1e-6f);
    hit = trace(load("disk_mirror", placed("d", "<scale value=\"1, 1, -1\"/>")), {0.3f, 0.2f, 5.f}, {0.f, 0.f, -1.f});
    EXPECT_NEAR(hit.ng.z, 1.f, 1e-6f);  // flipped, then mirrored back
    // An instance that collapses the disk is refused, naming it.
    EXPECT_NE(errorOf("disk_flat", placed("d", "<matrix value=\"1 1 0 0 0 1e-7 0 0 0 0 1 0 0 0 0 1\"/>"))
                  .find("disk \"disk at line 5\" of shapegroup \"d\" under this instance's to_world: the disk's "
                        "to_world is degenerate"),
              std::string::npos);
}

TEST(ShapeGroup, InstancesCopyABoundedNumberOfShapes) {
    // One copy short of the bound (2^20 shapes): one instance of a one-sphere group fits, the next does not.
    XmlContext ctx;
    ctx.file = "bound.xml";
    ctx.text = "<shape type=\"instance\"><ref id=\"g\"/></shape>";
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(ctx.text.c_str()));
    Definitions defs;
    defs.groups["g"].spheres.resize(1);
    defs.instancedShapes = (uint64_t(1) << 20) - 1;
    SceneDescription scene;
    loadInstance(ctx, doc.first_child(), defs, scene);
    EXPECT_EQ(scene.spheres.size(), 1u);
    try {
        loadInstance(ctx, doc.first_child(), defs, scene);
        ADD_FAILURE() << "the copy past the bound loaded";
    } catch (const SceneError &e) {
        EXPECT_NE(std::string(e.what()).find("bound.xml:1: "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("at most 2^28 triangles and 2^20 shapes"), std::string::npos);
    }
}

struct BadGroup {
    const char *name;
    std::string shapes;
    const char *expected;  ///< a fragment of the message
    int line;
};

void PrintTo(const BadGroup &c, std::ostream *os) { *os << c.name; }

class ShapeGroupErrors : public ::testing::TestWithParam<BadGroup> {};

TEST_P(ShapeGroupErrors, NameTheLineAndWhatWasExpected) {
    const std::string message = errorOf(GetParam().name, GetParam().shapes);
    EXPECT_NE(message.find(".xml:" + std::to_string(GetParam().line) + ": "), std::string::npos) << message;
    EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
}

std::vector<BadGroup> badGroups() {
    const std::string rect = "<shape type=\"rectangle\"/>";
    return {
        {"nested_group", "<shape type=\"shapegroup\" id=\"a\">\n<shape type=\"shapegroup\" id=\"b\">" + rect +
                             "</shape></shape>\n",
         "a shapegroup inside a shapegroup", 4},
        {"instance_in_group", kGroup + "<shape type=\"shapegroup\" id=\"h\">\n<shape type=\"instance\"><ref "
                                       "id=\"g\"/></shape></shape>\n",
         "an instance inside a shapegroup", 9},
        {"area_emitter_in_group", "<shape type=\"shapegroup\" id=\"a\"><shape type=\"rectangle\">\n<emitter "
                                  "type=\"area\"/></shape></shape>\n",
         "Mitsuba does not instance emitters", 4},
        {"emitter_in_group", "<shape type=\"shapegroup\" id=\"a\">\n<emitter type=\"point\"/></shape>\n",
         "an emitter inside a shapegroup", 4},
        {"bsdf_in_group", "<shape type=\"shapegroup\" id=\"a\">\n<bsdf type=\"diffuse\"/></shape>\n",
         "expected <shape>", 4},
        {"unknown_id", kGroup + "<shape type=\"instance\">\n<ref id=\"h\"/></shape>\n",
         "no <shape type=\"shapegroup\" id=\"h\"> in the file", 9},
        {"inline_group", "<shape type=\"instance\">\n<shape type=\"shapegroup\">" + rect + "</shape></shape>\n",
         "an instance takes one <ref id=\"...\"> to a shapegroup", 4},
        {"group_as_bsdf", kGroup + "<shape type=\"cube\">\n<ref id=\"g\"/></shape>\n",
         "names a shapegroup: only a <shape type=\"instance\"> may refer to one", 9},
        {"two_refs", kGroup + "<shape type=\"instance\">\n<ref id=\"g\"/><ref id=\"g\"/></shape>\n",
         "an instance takes one <ref id=\"...\"> to a shapegroup", 9},
        {"bsdf_in_instance", kGroup + "<shape type=\"instance\">\n<bsdf type=\"diffuse\"/></shape>\n",
         "an instance takes one <ref id=\"...\"> to a shapegroup", 9},
        {"uneven_scale_on_a_sphere", kGroup + "<shape type=\"instance\"><ref id=\"g\"/>\n<transform "
                                              "name=\"to_world\"><scale value=\"1, 2, 1\"/></transform></shape>\n",
         "under this instance's to_world: a sphere's to_world may only translate, rotate and scale uniformly", 8},
        {"duplicate_id", kGroup + "<shape type=\"shapegroup\" id=\"g\">" + rect + "</shape>\n",
         "the id \"g\" is already defined", 8},
        {"to_world_on_group", "<shape type=\"shapegroup\" id=\"a\">\n<transform name=\"to_world\"><scale "
                              "value=\"2\"/></transform>" + rect + "</shape>\n",
         "Mitsuba ignores its to_world", 4},
    };
}

INSTANTIATE_TEST_SUITE_P(Refused, ShapeGroupErrors, ::testing::ValuesIn(badGroups()),
                         [](const auto &info) { return std::string(info.param.name); });
