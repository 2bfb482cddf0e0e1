// Packets whose inactive lanes hold NaN or were never set: Embree's AVX2 kernels (16 rays as two packets of 8)
// assert on such a lane although it is masked out (an abort of the whole render), so each trace gives them a
// finite, empty ray; the active lanes' answers are the single rays'.
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "embree_scene.h"
#include "mesh.h"
#include "transform.h"

using namespace mcval;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();

/// A 2 x 2 square in the plane z = 0, facing +z.
std::vector<Mesh> square() { return {makeRectangle(Transform())}; }

}  // namespace

TEST(InactiveLanes, ANaNOrAnUnsetLaneIsLeftOutOfAClosestHitPacket) {
    const std::vector<Mesh> meshes = square();
    const EmbreeScene scene(meshes);
    RayHitPacket packet;  // lanes 2.. never set
    packet.set(0, true, {0.2f, 0.1f, 3.f}, {0.f, 0.f, -1.f}, 0.f, 1e30f);
    packet.set(1, false, {kNaN, kNaN, kNaN}, {kNaN, kNaN, kNaN}, kNaN, kNaN);
    HitPacket hits;
    scene.intersect(packet, 2, hits);
    ASSERT_TRUE(hits.found[0]);
    EXPECT_NEAR(hits.hit(0).t, 3.f, 1e-6f);
    EXPECT_FALSE(hits.found[1]);
}

TEST(InactiveLanes, ANaNLaneIsLeftOutOfAStreamAndOfAnOcclusionPacket) {
    const std::vector<Mesh> meshes = square();
    const EmbreeScene scene(meshes);
    RayHitPacket packets[2];
    for (RayHitPacket &p : packets) {
        p.set(0, true, {0.2f, 0.1f, 3.f}, {0.f, 0.f, -1.f}, 0.f, 1e30f);
        for (int i = 1; i < kPacketSize; ++i) p.set(i, false, {kNaN, 0.f, 0.f}, {0.f, kNaN, 0.f}, kNaN, kNaN);
    }
    const int counts[2] = {kPacketSize, kPacketSize};
    HitPacket hits[2];
    scene.intersect(packets, counts, 2, hits);
    for (const HitPacket &h : hits) {
        ASSERT_TRUE(h.found[0]);
        for (int i = 1; i < kPacketSize; ++i) EXPECT_FALSE(h.found[i]) << i;
    }
    OcclusionPacket shadow;
    shadow.set(0, {0.2f, 0.1f, 3.f}, {0.f, 0.f, -1.f}, 10.f);
    shadow.rays.org_x[1] = kNaN;  // a lane a caller filled and then left inactive
    scene.occluded(shadow, true);
    EXPECT_TRUE(shadow.blocked(0));
    EXPECT_FALSE(shadow.blocked(1));
}
