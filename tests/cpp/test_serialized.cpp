// Mitsuba's .serialized meshes: files of our own (serialized_writer.h) load exactly, in both versions,
// precisions and with every optional array; every damaged one gives a SceneError naming the problem.
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "embree_scene.h"
#include "error.h"
#include "temp_files.h"
#include "mesh.h"
#include "scene.h"
#include "serialized_reader.h"
#include "serialized_writer.h"

using namespace mcval;
using namespace mcval::test;
namespace fs = std::filesystem;

namespace {

/// A folder of its own per process, removed after the last test.
fs::path tempDir() { return mcval::test::tempFolder("mcval_serialized_"); }
[[maybe_unused]] ::testing::Environment *const kCleanup =
    ::testing::AddGlobalTestEnvironment(
        new mcval::test::TempFolderCleanup(mcval::test::tempFolderPath("mcval_serialized_")));

std::string writeFile(const std::string &name, const std::string &bytes) {
    return mcval::test::writeFileIn(tempDir(), name, bytes);
}

/// The SceneError message of reading shape `index` of the bytes, or "" if it reads.
std::string errorOf(const std::string &bytes, uint32_t index = 0) {
    try {
        readSerialized("bad.serialized", bytes, index);
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

/// Where a one-shape file's table starts: the end of its zlib stream.
size_t streamEndOf(const std::string &file) { return file.size() - 12; }

void expectNear(const Vec3f &a, const Vec3f &b) {
    EXPECT_NEAR(a.x, b.x, 1e-6f);
    EXPECT_NEAR(a.y, b.y, 1e-6f);
    EXPECT_NEAR(a.z, b.z, 1e-6f);
}

}  // namespace

TEST(Serialized, ASquareWithEveryArrayReadsExactlyInBothPrecisions) {
    for (bool doubles : {false, true}) {
        SerializedShape s = square();
        s.doubles = doubles;
        s.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        s.texcoords = {0, 0, 1, 0, 1, 1, 0, 1};  // read past: the indices after them must still be right
        s.colors = std::vector<double>(12, 0.5);
        const Mesh mesh = readSerialized("square.serialized", serializedFile({s}), 0);
        ASSERT_EQ(mesh.positions.size(), 4u);
        expectNear(mesh.positions[2], {1, 1, 0});
        ASSERT_EQ(mesh.normals.size(), 4u);
        expectNear(mesh.normals[3], {0, 0, 1});
        EXPECT_EQ(mesh.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    }
}

TEST(Serialized, ShapeIndexPicksTheShapeFromTheTableInVersionsThreeAndFour) {
    for (uint16_t version : {3, 4}) {
        std::vector<SerializedShape> shapes = {square(0), square(10), square(20)};
        for (auto &s : shapes) s.version = version;
        const std::string bytes = serializedFile(shapes);
        for (uint32_t i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(readSerialized("f", bytes, i).positions[0].x, 10.f * i);
        EXPECT_NE(errorOf(bytes, 3).find("shape_index 3 is out of range: the file holds 3 shape(s)"),
                  std::string::npos);
    }
    // Read with the other version's table, shape 1's offset is wrong: the planted defect is caught.
    std::vector<SerializedShape> shapes = {square(0), square(10)};
    std::string bytes = serializedFile(shapes);  // version 4: u64 offsets
    bytes[2] = 3;                                // claims version 3: u32 offsets
    EXPECT_NE(errorOf(bytes, 1), "");
}

TEST(Serialized, TheSceneLoaderTransformsFlipsAndShadesAsForOtherMeshes) {
    const std::string path = writeFile("square.serialized", serializedFile({square()}));
    const Transform lift = Transform::translate({0, 0, 2});
    // No normals in the file: Mitsuba's vertex normals, along +z for a flat square.
    const Mesh smooth = loadSerializedFile(path, 0, lift, false, false);
    ASSERT_EQ(smooth.normals.size(), 4u);
    expectNear(smooth.normals[0], {0, 0, 1});
    expectNear(smooth.positions[2], {1, 1, 2});
    EXPECT_TRUE(loadSerializedFile(path, 0, lift, true, false).normals.empty());
    const Mesh flipped = loadSerializedFile(path, 0, lift, false, true);
    expectNear(flipped.normals[0], {0, 0, -1});
    EXPECT_EQ(flipped.indices, (std::vector<uint32_t>{0, 2, 1, 0, 3, 2}));

    // Traced: a ray down onto the lifted square hits at z = 2 from the front; flipped, from the back.
    for (bool flip : {false, true}) {
        const std::vector<Mesh> meshes = {loadSerializedFile(path, 0, lift, true, flip)};
        const EmbreeScene embree(meshes);
        Ray ray;
        ray.o = {0.25f, 0.5f, 5.f};
        ray.d = {0.f, 0.f, -1.f};
        Hit hit;
        ASSERT_TRUE(embree.intersect(ray, hit));
        EXPECT_NEAR(hit.t, 3.f, 1e-5f);
        EXPECT_FLOAT_EQ(hit.ng.z, flip ? -1.f : 1.f);
    }
}

TEST(Serialized, MitsubasOwnSamplesLoadWhereTheyAreInstalled) {
    const std::string rectangle = "/tmp/mdata/tests/serialized/rectangle_normals_uv.serialized";
    const std::string matpreview = "/tmp/mdata/common/meshes/matpreview.serialized";
    if (!fs::exists(rectangle) || !fs::exists(matpreview)) GTEST_SKIP() << "Mitsuba's test data is not here";
    const Mesh mesh = loadSerializedFile(rectangle, 0, Transform(), false, false);
    EXPECT_EQ(mesh.indices.size(), 6u);
    for (uint32_t i = 0; i < 3; ++i)
        EXPECT_GT(loadSerializedFile(matpreview, i, Transform(), false, false).indices.size(), 0u);
    EXPECT_THROW(loadSerializedFile(matpreview, 3, Transform(), false, false), SceneError);
}

TEST(Serialized, EveryTruncationAndSeededDamageIsAMeshOrASceneError) {
    SerializedShape normals = square(5);
    normals.normals = std::vector<double>(12, 0.0);
    normals.doubles = true;
    const std::string good = serializedFile({square(), normals});
    const size_t secondShape = 4 + serializedPayload(square()).size();
    // Whether reading shape `index` is a SceneError; a mesh it gives back must be consistent.
    const auto refused = [](const std::string &bytes, uint32_t index) {
        try {
            const Mesh mesh = readSerialized("damaged", bytes, index);
            for (uint32_t i : mesh.indices) EXPECT_LT(i, mesh.positions.size());
            EXPECT_TRUE(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size());
            return false;
        } catch (const SceneError &) {
            return true;
        }
    };
    for (size_t n = 0; n < good.size(); ++n) {
        EXPECT_EQ(refused(good.substr(0, n), 0), n < secondShape) << n;  // the first shape needs no table
        EXPECT_TRUE(refused(good.substr(0, n), 1)) << n;
    }
    std::mt19937 rng(7);
    for (int trial = 0; trial < 3000; ++trial) {
        std::string bytes = good;
        for (int k = 1 + int(rng() % 3); k > 0; --k) bytes[rng() % bytes.size()] = char(rng());
        refused(bytes, trial % 2);
    }
}

struct BadFile {
    const char *name;
    std::string bytes;
    const char *expected;  ///< a fragment of the message
    uint32_t index = 0;
};

void PrintTo(const BadFile &c, std::ostream *os) { *os << c.name; }

class SerializedErrors : public ::testing::TestWithParam<BadFile> {};

TEST_P(SerializedErrors, AreSceneErrorsNamingTheFileAndWhatWasExpected) {
    const std::string message = errorOf(GetParam().bytes, GetParam().index);
    EXPECT_EQ(message.rfind("bad.serialized: ", 0), 0u) << message;
    EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
}

std::vector<BadFile> badFiles() {
    const std::string good = serializedFile({square()});
    const auto with = [](auto change) {
        SerializedShape s = square();
        change(s);
        return serializedFile({s});
    };
    std::string corrupt = good;
    for (size_t i = 12; i < 20; ++i) corrupt[i] = char(~corrupt[i]);
    std::string checksum = good;
    checksum[streamEndOf(good) - 1] ^= 1;  // the last byte of the stream: its Adler-32
    std::string badOffset = serializedFile({square(), square(1)});
    badOffset[badOffset.size() - 12] = char(0x7f);  // shape 1's u64 offset, low byte
    badOffset[badOffset.size() - 6] = char(0x7f);   // and a high byte
    SerializedShape badMagic = square();
    badMagic.magic = 7;
    return {
        {"empty", "", "too short for a serialized mesh header"},
        {"bad header", with([](SerializedShape &s) { s.magic = 0x041D; }), "expected the header 0x041C"},
        {"version 5", with([](SerializedShape &s) { s.version = 5; }), "version 5: expected 3 or 4"},
        {"version 2", with([](SerializedShape &s) { s.version = 2; }), "version 2: expected 3 or 4"},
        {"truncated", good.substr(0, good.size() - 30), "ends before"},
        {"only the header", good.substr(0, 4), "ends before shape 0's flags"},
        {"inflate error", corrupt, "corrupt compressed data"},
        {"checksum", checksum, "corrupt compressed data after shape 0's triangle indices: incorrect data check"},
        {"vertex count past the data", with([](SerializedShape &s) { s.vertexCount = 1000; }),
         "ends before shape 0's vertex positions"},
        {"counts past what the file can hold", with([](SerializedShape &s) { s.vertexCount = 1000000; }),
         "more than its 57 compressed bytes can hold"},
        {"triangle count past the data", with([](SerializedShape &s) { s.faceCount = 3; }),
         "ends before shape 0's triangle indices"},
        {"huge vertex count", with([](SerializedShape &s) { s.vertexCount = uint64_t(1) << 40; }),
         "at most 2^28 of each"},
        {"huge triangle count", with([](SerializedShape &s) { s.faceCount = ~uint64_t(0); }), "at most 2^28 of each"},
        {"triangle count too small", with([](SerializedShape &s) { s.faceCount = 1; }),
         "goes on after shape 0's triangle indices"},
        {"no triangles", with([](SerializedShape &s) { s.indices.clear(); }), "has no triangles"},
        {"index out of range", with([](SerializedShape &s) { s.indices[4] = 4; }),
         "triangle 1 uses vertex 4, but there are 4"},
        {"unterminated name", with([](SerializedShape &s) { s.name = std::string(70000, 'n'); }),
         "name is longer than 65536 bytes"},
        {"shape index past the table", good, "shape_index 1 is out of range: the file holds 1", 1},
        {"offset past the data", badOffset, "the offset of shape 1", 1},
        {"table longer than the file", good.substr(0, good.size() - 4) + std::string("\xff\xff\xff\x00", 4),
         "shape offsets is longer than the file", 2},
        {"sub-shape header", serializedFile({square(), badMagic}), "does not start with the file's header", 1},
    };
}

INSTANTIATE_TEST_SUITE_P(Damaged, SerializedErrors, ::testing::ValuesIn(badFiles()),
                         [](const auto &info) {
                             std::string name = info.param.name;
                             for (char &c : name) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                             return name;
                         });
