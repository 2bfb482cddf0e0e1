// Packet tracing: up to kPacketSize rays in one Embree call, laid out as its SoA packets. Embree
// traverses a coherent packet's BVH nodes once for all its rays, with the machine's widest SIMD.
#include <limits>

#include "embree_scene.h"
#include "error.h"
#include "hot.h"

namespace mcval {

namespace {

/// Writes ray `r` into lane i of an Embree SoA ray packet.
template <typename Packet>
void setLane(Packet &p, int i, const Ray &r) {
    p.org_x[i] = r.o.x; p.org_y[i] = r.o.y; p.org_z[i] = r.o.z;
    p.dir_x[i] = r.d.x; p.dir_y[i] = r.d.y; p.dir_z[i] = r.d.z;
    p.tnear[i] = r.tnear;
    p.tfar[i] = r.tfar;
    p.time[i] = 0.f;
    p.mask[i] = std::numeric_limits<unsigned>::max();
    p.id[i] = 0;
    p.flags[i] = 0;
}

}  // namespace

OcclusionPacket::OcclusionPacket() {
    for (int i = 0; i < kPacketSize; ++i) {
        rays.time[i] = 0.f;
        rays.mask[i] = std::numeric_limits<unsigned>::max();
        rays.id[i] = 0;
        rays.flags[i] = 0;
        valid[i] = 0;
    }
}

RayHitPacket::RayHitPacket() {
    for (int i = 0; i < kPacketSize; ++i) {
        rh.ray.time[i] = 0.f;
        rh.ray.mask[i] = std::numeric_limits<unsigned>::max();
        rh.ray.id[i] = 0;
        rh.ray.flags[i] = 0;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        valid[i] = 0;
    }
}

MCVAL_HOT void EmbreeScene::intersect(RayHitPacket &packet, int count, Ray *rays, Hit *hits, bool *found) const {
    MCR_ASSERT(count > 0 && count <= kPacketSize);
    alignas(64) float tfar[kPacketSize];
    for (int i = 0; i < kPacketSize; ++i) tfar[i] = packet.rh.ray.tfar[i];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(packet.valid, m_scene, &context, &packet.rh);
    const RTCHit16 &h = packet.rh.hit;
    for (int i = 0; i < count; ++i) {
        rays[i] = packet.ray(i, tfar[i]);
        found[i] = h.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        if (found[i]) fillHit(rays[i], h.geomID[i], h.primID[i], h.u[i], h.v[i], packet.rh.ray.tfar[i], hits[i]);
    }
}

void EmbreeScene::occluded(OcclusionPacket &packet, bool coherent) const {
    if (packet.active == 0) return;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (coherent) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded16(packet.valid, m_scene, &context, &packet.rays);
}

MCVAL_HOT void EmbreeScene::intersect16(const Ray *rays, int count, Hit *hits, bool *found) const {
    MCR_ASSERT(count > 0 && count <= kPacketSize);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[kPacketSize];
    alignas(64) RTCRayHit16 rh;
    for (int i = 0; i < kPacketSize; ++i) {
        valid[i] = i < count ? -1 : 0;
        setLane(rh.ray, i, rays[i < count ? i : 0]);
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, m_scene, &context, &rh);
    for (int i = 0; i < count; ++i) {
        found[i] = rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        if (found[i]) fillHit(rays[i], rh.hit.geomID[i], rh.hit.primID[i], rh.hit.u[i], rh.hit.v[i], rh.ray.tfar[i], hits[i]);
    }
}

void EmbreeScene::occluded16(const Ray *rays, const bool *active, int count, bool *blocked, bool coherent) const {
    MCR_ASSERT(count > 0 && count <= kPacketSize);
    alignas(64) int valid[kPacketSize];
    alignas(64) RTCRay16 r;
    int first = -1;
    for (int i = 0; i < count && first < 0; ++i)
        if (active[i]) first = i;
    for (int i = 0; i < count; ++i) blocked[i] = false;
    if (first < 0) return;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (coherent) context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    for (int i = 0; i < kPacketSize; ++i) {
        const bool on = i < count && active[i];
        valid[i] = on ? -1 : 0;
        setLane(r, i, rays[on ? i : first]);
    }
    rtcOccluded16(valid, m_scene, &context, &r);
    for (int i = 0; i < count; ++i) blocked[i] = active[i] && r.tfar[i] < 0.f;  // Embree sets tfar to -inf on a hit
}

}  // namespace mcval
