// Mesh files: valid PLY (ascii, both binary byte orders) and OBJ load exactly; every damaged or
// unusual input gives a SceneError naming the problem, never a crash or a hang.
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "error.h"
#include "temp_files.h"
#include "mesh.h"
#include "obj_reader.h"
#include "ply_reader.h"

using namespace mcval;
namespace fs = std::filesystem;

namespace {

/// A folder of its own per process, removed after the last test.
fs::path tempDir() { return mcval::test::tempFolder("mcval_mesh_"); }
[[maybe_unused]] ::testing::Environment *const kCleanup =
    ::testing::AddGlobalTestEnvironment(
        new mcval::test::TempFolderCleanup(mcval::test::tempFolderPath("mcval_mesh_")));

std::string writeFile(const std::string &name, const std::string &bytes) {
    return mcval::test::writeFileIn(tempDir(), name, bytes);
}

/// The SceneError message of loading the file, or "" if it loads.
std::string errorOf(const std::string &path) {
    try {
        loadMeshFile(path, Transform(), false);
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

std::string errorOfBytes(const std::string &name, const std::string &bytes) { return errorOf(writeFile(name, bytes)); }

/// Appends v in little or big endian.
template <class T> void put(std::string &out, T v, bool bigEndian) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    for (size_t i = 0; i < sizeof(T); ++i) out += b[bigEndian ? sizeof(T) - 1 - i : i];
}

// A unit square in z = 0 as two triangles, plus a lone vertex 4.
const float kPos[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 2, 2}};
const int32_t kTris[2][3] = {{0, 1, 2}, {0, 2, 3}};

/// A binary PLY with extra vertex properties, an extra element with a list between vertices and
/// faces, and an extra face property.
std::string binaryPly(bool bigEndian, bool normals) {
    std::string s = std::string("ply\nformat ") + (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\ncomment made by a test\nobj_info nothing\nelement vertex 5\n"
                    "property float x\nproperty float y\nproperty float z\n";
    if (normals) s += "property float nx\nproperty float ny\nproperty float nz\n";
    s += "property uchar red\nproperty double u\nelement edge 2\nproperty int a\nproperty list uchar float w\n"
         "element face 2\nproperty list uchar int vertex_indices\nproperty short flags\nend_header\n";
    for (const auto &p : kPos) {
        for (float c : p) put(s, c, bigEndian);
        if (normals) put(s, 0.f, bigEndian), put(s, 0.f, bigEndian), put(s, 1.f, bigEndian);
        put(s, uint8_t(200), bigEndian);
        put(s, 0.25, bigEndian);
    }
    for (int e = 0; e < 2; ++e) {
        put(s, int32_t(7), bigEndian);
        put(s, uint8_t(e + 1), bigEndian);
        for (int k = 0; k <= e; ++k) put(s, 9.f, bigEndian);
    }
    for (const auto &t : kTris) {
        put(s, uint8_t(3), bigEndian);
        for (int32_t i : t) put(s, i, bigEndian);
        put(s, int16_t(-1), bigEndian);
    }
    return s;
}

void expectSquare(const Mesh &m, bool normals) {
    ASSERT_EQ(m.positions.size(), 5u);
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(m.positions[i].x, kPos[i][0]);
        EXPECT_EQ(m.positions[i].y, kPos[i][1]);
        EXPECT_EQ(m.positions[i].z, kPos[i][2]);
    }
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(m.normals.size(), normals ? 5u : 0u);
    for (const Vec3f &n : m.normals) EXPECT_EQ(n.z, 1.f);
}

/// A small ascii PLY whose face lines are given.
std::string asciiPly(const std::string &faces, int faceCount, const std::string &vertex4 = "2 2 2") {
    return "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
           "element face " + std::to_string(faceCount) + "\nproperty list uchar int vertex_indices\nend_header\n"
           "0 0 0\n1 0 0\n1 1 0\n0 1 0\n" + vertex4 + "\n" + faces;
}

const std::string kObj = "# two triangles sharing an edge\nmtllib none.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                         "vn 0 0 1\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n";

}  // namespace

TEST(MeshReader, AsciiPlyLoads) {
    const Mesh m = readPly("a.ply", asciiPly("3 0 1 2\n3 0 2 3\n", 2));
    expectSquare(m, false);
    const Mesh world = loadMeshFile(writeFile("ascii.ply", asciiPly("3 0 1 2\n3 0 2 3\n", 2)), Transform(), false);
    ASSERT_EQ(world.normals.size(), 5u);  // computed
    EXPECT_FLOAT_EQ(world.normals[0].z, 1.f);
}

TEST(MeshReader, BinaryLittleEndianPlyWithAndWithoutNormals) {
    expectSquare(readPly("le.ply", binaryPly(false, true)), true);
    expectSquare(readPly("le.ply", binaryPly(false, false)), false);
}

TEST(MeshReader, BinaryBigEndianPlyWithAndWithoutNormals) {
    expectSquare(readPly("be.ply", binaryPly(true, true)), true);
    expectSquare(readPly("be.ply", binaryPly(true, false)), false);
}

TEST(MeshReader, PolygonsAreFanTriangulated) {
    const Mesh m = readPly("quad.ply", asciiPly("4 0 1 2 3\n5 0 1 2 3 4\n", 2));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3, 0, 3, 4}));
}

TEST(MeshReader, ObjJoinsSharedCorners) {
    const Mesh m = readObj("a.obj", kObj);
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    ASSERT_EQ(m.normals.size(), 4u);
    // A corner with another normal is another vertex; a corner without one drops all normals.
    const Mesh split = readObj("b.obj", kObj + "vn 1 0 0\nf 1//2 3//1 4//1\n");
    EXPECT_EQ(split.positions.size(), 5u);
    EXPECT_EQ(split.normals.size(), 5u);
    const Mesh bare = readObj("c.obj", kObj + "f 1 2 3\n");
    EXPECT_EQ(bare.positions.size(), 7u);
    EXPECT_TRUE(bare.normals.empty());
    EXPECT_EQ(loadMeshFile(writeFile("shared.obj", kObj), Transform(), false).positions.size(), 4u);
}

TEST(MeshReader, IndexOutOfRange) {
    const std::string e = errorOfBytes("range.ply", asciiPly("3 0 1 2\n3 0 2 4096\n", 2));
    EXPECT_NE(e.find("face 1 (line 16): vertex index 4096 out of range (the mesh has 5 vertices)"), std::string::npos) << e;
}

TEST(MeshReader, IndexOutOfRangeWithNormals) {
    std::string s = binaryPly(false, true);
    s[s.size() - 6] = 5;  // the last index of the last face (before its 2-byte flags)
    const std::string e = errorOfBytes("range_normals.ply", s);
    EXPECT_NE(e.find("face 1: vertex index 5 out of range"), std::string::npos) << e;
}

TEST(MeshReader, NegativeIndex) {
    const std::string e = errorOfBytes("negative.ply", asciiPly("3 0 1 -1\n3 0 2 3\n", 2));
    EXPECT_NE(e.find("vertex index -1 out of range"), std::string::npos) << e;
}

TEST(MeshReader, TruncatedBinaryData) {
    const std::string s = binaryPly(false, false);
    EXPECT_NE(errorOfBytes("cut_faces.ply", s.substr(0, s.size() - 3)).find("file ends inside the face data (face 1 of 2)"),
              std::string::npos);
    const size_t header = s.find("end_header\n") + 11;
    // Fixed-size vertices: the cut shows before reading, as records the rest of the file cannot hold.
    const std::string e = errorOfBytes("cut_vertices.ply", s.substr(0, header + 40));
    EXPECT_NE(e.find("element vertex declares 5 records, but the 40 bytes after the header cannot hold them"),
              std::string::npos) << e;
}

TEST(MeshReader, HeaderWithoutEndHeader) {
    const std::string s = binaryPly(false, false);
    EXPECT_NE(errorOfBytes("cut_header.ply", s.substr(0, 60)).find("end_header"), std::string::npos);
    // A long header that never ends is refused after a bounded read.
    std::string endless = "ply\nformat ascii 1.0\n";
    while (endless.size() < 100000) endless += "comment padding padding padding\n";
    EXPECT_NE(errorOfBytes("endless.ply", endless).find("no end_header in the first 65536 bytes"), std::string::npos);
}

TEST(MeshReader, CountLargerThanFileCanHold) {
    std::string s = binaryPly(false, false);
    s.replace(s.find("element vertex 5"), 16, "element vertex 200000000");
    const std::string e = errorOfBytes("huge_count.ply", s);
    EXPECT_NE(e.find("element vertex declares 200000000 records"), std::string::npos) << e;
    s.replace(s.find("element vertex 200000000"), 24, "element vertex 99999999999");
    EXPECT_NE(errorOfBytes("huge_count2.ply", s).find("at most 2^28"), std::string::npos);
}

TEST(MeshReader, UnknownFormat) {
    std::string s = asciiPly("3 0 1 2\n", 1);
    s.replace(s.find("ascii"), 5, "binary_middle_endian");
    EXPECT_NE(errorOfBytes("format.ply", s).find("unknown format \"binary_middle_endian\""), std::string::npos);
}

TEST(MeshReader, UnknownType) {
    std::string s = asciiPly("3 0 1 2\n", 1);
    s.replace(s.find("property float y"), 16, "property flaot y");
    EXPECT_NE(errorOfBytes("type.ply", s).find("header line 5: unknown type \"flaot\""), std::string::npos);
}

TEST(MeshReader, NanCoordinate) {
    const std::string e = errorOfBytes("nan.ply", asciiPly("3 0 1 2\n", 1, "2 nan 2"));
    EXPECT_NE(e.find("vertex 4 (line 14): position is not finite"), std::string::npos) << e;
    std::string s = binaryPly(true, false);
    const size_t v1 = s.find("end_header\n") + 11 + 12 + 1 + 8;  // vertex 1's x
    for (int k = 0; k < 4; ++k) s[v1 + k] = "\x7f\xc0\x00\x00"[k];  // NaN, big endian
    EXPECT_NE(errorOfBytes("nan_be.ply", s).find("vertex 1: position is not finite"), std::string::npos);
}

TEST(MeshReader, EmptyFile) { EXPECT_NE(errorOfBytes("empty.ply", "").find("the file is empty"), std::string::npos); }

TEST(MeshReader, FifoIsRefusedWithoutBlocking) {
    const fs::path fifo = tempDir() / "pipe.ply";
    fs::remove(fifo);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Should the reader block on the FIFO, a writer frees it after 2 s and the time check fails.
    std::atomic<bool> done{false};
    std::thread unblocker([&] {
        for (int i = 0; i < 200 && !done; ++i) {
            const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (fd >= 0 && i >= 100) return void(::close(fd));
            if (fd >= 0) ::close(fd);
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
    });
    const auto start = std::chrono::steady_clock::now();
    const std::string e = errorOf(fifo.string());
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    done = true;
    unblocker.join();
    EXPECT_NE(e.find("is a FIFO"), std::string::npos) << e;
    EXPECT_LT(seconds, 0.5);
    fs::remove(fifo);
}

TEST(MeshReader, DirectoryIsRefused) {
    const fs::path dir = tempDir() / "folder.ply";
    fs::create_directories(dir);
    EXPECT_NE(errorOf(dir.string()).find("is a directory"), std::string::npos);
}

TEST(MeshReader, SymlinkToAFileLoads) {
    const fs::path link = tempDir() / "link.ply";
    fs::remove(link);
    fs::create_symlink(writeFile("target.ply", binaryPly(false, true)), link);
    EXPECT_EQ(loadMeshFile(link.string(), Transform(), false).indices.size(), 6u);
}

TEST(MeshReader, OverlyLongPathIsASceneError) {
    const std::string e = errorOf((tempDir() / (std::string(5000, 'a') + ".ply")).string());
    EXPECT_NE(e.find("cannot read mesh file"), std::string::npos) << e.substr(e.size() - 80);
}

TEST(MeshReader, ObjIndexOutOfRange) {
    const std::string e = errorOfBytes("range.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 1 2 9\n");
    EXPECT_NE(e.find("face 2: vertex index 9 out of range (the file defines 3 before it)"), std::string::npos) << e;
    EXPECT_NE(errorOfBytes("range_normal.obj", kObj + "f 1//2 2//1 3//1\n").find("normal index 2 out of range"),
              std::string::npos);
    EXPECT_NE(errorOfBytes("inf.obj", "v 0 1e999 0\n").find("vertex 1 is not finite"), std::string::npos);
}

TEST(MeshReader, TruncatedObj) {
    EXPECT_NE(errorOfBytes("cut.obj", kObj.substr(0, kObj.size() - 8)).find("face 2 has 2 vertices"), std::string::npos);
    EXPECT_NE(errorOfBytes("cut_early.obj", kObj.substr(0, 60)).find("mesh has no triangles"), std::string::npos);
}

TEST(MeshReader, TruncatedRealMeshLoadsOrFailsCleanly) {
    // A mesh of the scenes when generated; otherwise the test's own binary PLY.
    const fs::path real = fs::path(MCVAL_SOURCE_DIR) / "scenes" / "meshes" / "sphere.ply";
    std::ifstream in(real, std::ios::binary);
    const std::string full = in ? std::string(std::istreambuf_iterator<char>(in), {}) : binaryPly(false, true);
    const size_t header = full.find("end_header\n") + 11;
    std::vector<size_t> cuts;
    for (size_t i = 0; i < 20; ++i) cuts.push_back(i * header / 20);                         // inside the header
    for (size_t i = 0; i < 30; ++i) cuts.push_back(header + i * (full.size() - header) / 30);  // inside the data
    cuts.push_back(full.size() - 1);
    const auto start = std::chrono::steady_clock::now();
    for (const size_t cut : cuts) {
        const std::string path = writeFile("cut_" + std::to_string(cut) + ".ply", full.substr(0, cut));
        try {
            loadMeshFile(path, Transform(), false);
        } catch (const SceneError &) {
        }
        fs::remove(path);
    }
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
    EXPECT_NO_THROW(loadMeshFile(writeFile("whole.ply", full), Transform(), false));
    for (size_t cut = 0; cut < kObj.size(); ++cut) {
        try {
            readObj("cut.obj", kObj.substr(0, cut));
        } catch (const SceneError &) {
        }
    }
}
