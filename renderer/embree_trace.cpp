// Tracing: single rays, and packets of up to kPacketSize rays in one Embree call, laid out as its
// SoA packets (Embree traverses a coherent packet's BVH nodes once for all its rays, with the
// machine's widest SIMD); and the hit records made from Embree's answers.
#include <limits>

#include "cylinder.h"
#include "disk.h"
#include "embree_scene.h"
#include "error.h"
#include "sphere.h"
#include "hot.h"

namespace mcval {

namespace {

/// The fields of lane i of an Embree SoA ray packet that no ray of ours varies.
template <typename Packet>
void setFixedFields(Packet &p, int i) {
    p.time[i] = 0.f;
    p.mask[i] = std::numeric_limits<unsigned>::max();
    p.id[i] = 0;
    p.flags[i] = 0;
}

/// Lane i as a finite, empty ray. Every inactive lane gets one: Embree's AVX2 kernels (16 rays as two packets
/// of 8) assert on a NaN, or on what was left in memory, in an inactive lane too, and a caller's unused lane may
/// hold either (simple's unlit lane where the light sits on its point: fuzz corpus light_on_floor; a lane never
/// set).
template <typename Packet>
void setEmptyRay(Packet &p, int i) {
    p.org_x[i] = p.org_y[i] = p.org_z[i] = 0.f;
    p.dir_x[i] = p.dir_y[i] = 0.f;
    p.dir_z[i] = 1.f;
    p.tnear[i] = p.tfar[i] = 0.f;
}

/// Writes ray `r` into lane i of an Embree SoA ray packet.
template <typename Packet>
void setLane(Packet &p, int i, const Ray &r) {
    p.org_x[i] = r.o.x; p.org_y[i] = r.o.y; p.org_z[i] = r.o.z;
    p.dir_x[i] = r.d.x; p.dir_y[i] = r.d.y; p.dir_z[i] = r.d.z;
    p.tnear[i] = r.tnear;
    p.tfar[i] = r.tfar;
    setFixedFields(p, i);
}

RTCRay toRtc(const Ray &ray) {
    RTCRay r;
    r.org_x = ray.o.x; r.org_y = ray.o.y; r.org_z = ray.o.z;
    r.dir_x = ray.d.x; r.dir_y = ray.d.y; r.dir_z = ray.d.z;
    r.tnear = ray.tnear;
    r.tfar = ray.tfar;
    r.time = 0.f;
    r.mask = std::numeric_limits<unsigned>::max();
    r.id = 0;
    r.flags = 0;
    return r;
}

}  // namespace

// Defined before the loops that call it and always inlined, so that each of their ISA clones has its own
// copy and the hit's fields stay in registers until they are stored.
__attribute__((always_inline)) inline void EmbreeScene::fillHit(const Ray &ray, unsigned geom, unsigned prim, float u, float v, float t, Hit &hit) const {
    hit.t = t;
    hit.geom = geom;
    hit.prim = prim;
    hit.offsetFloor = m_offsetFloor;
    hit.emitter = m_emitterOf[geom];
    if (geom >= m_meshes.size()) {
        // An exact shape: the exact point and normal; its shading normal is its geometric one.
        if (geom < m_firstDisk)
            sphereHitPoint(m_spheres[geom - m_meshes.size()], ray.o, ray.d, double(t) + double(u), hit.p, hit.ng);
        else
            diskCylinderHit(geom, ray.o, ray.d, double(t) + double(u), hit.p, hit.ng);
        hit.ns = hit.ng;
        return;
    }
    const TriangleRecord &tri = m_triangles[m_firstTriangle[geom] + prim];
    const float w = 1.f - u - v;
    hit.p = w * tri.p0 + u * tri.p1 + v * tri.p2;
    hit.ng = tri.ng;
    hit.offsetFloor = hitOffsetFloor(m_offsetFloor, tri.p0, tri.p1, tri.p2, w, u, v, tri.ng);
    if (m_firstNormals[geom] == kFlat) {
        hit.ns = hit.ng;
    } else {
        const TriangleNormals &n3 = m_normals[m_firstNormals[geom] + prim];
        const Vec3f n = w * n3.n0 + u * n3.n1 + v * n3.n2;
        const float len2 = squaredNorm(n);
        hit.ns = len2 > 0.f ? n / std::sqrt(len2) : hit.ng;
    }
}

// fillHit's arithmetic for the mesh lanes, in the same order (the same bits), over all lanes at once;
// then the lanes on a sphere.
MCVAL_HOT void EmbreeScene::fillHits(const RTCRayHit16 &rh, int count, HitPacket &hits) const {
    const RTCHit16 &h = rh.hit;
    const uint32_t meshes = static_cast<uint32_t>(m_meshes.size());
    const uint32_t none = static_cast<uint32_t>(m_triangles.size() - 1), noNormals = static_cast<uint32_t>(m_normals.size() - 1);
    const TriangleRecord *tris = m_triangles.data();
    const TriangleNormals *smooth = m_normals.data();
    const uint32_t *firstTriangle = m_firstTriangle.data(), *firstNormals = m_firstNormals.data();
    int spheres = 0, others = 0;  // lanes on a sphere, on a disk or a cylinder
    for (int i = 0; i < kPacketSize; ++i) {
        const bool found = (i < count) & (h.geomID[i] != RTC_INVALID_GEOMETRY_ID);
        const bool mesh = found & (h.geomID[i] < meshes);
        const uint32_t g = mesh ? h.geomID[i] : 0;
        const uint32_t first = mesh ? firstTriangle[g] : 0, firstN = mesh ? firstNormals[g] : kFlat;
        const TriangleRecord &tri = tris[mesh ? first + h.primID[i] : none];
        const bool isSmooth = firstN != kFlat;
        const TriangleNormals &n3 = smooth[isSmooth ? firstN + h.primID[i] : noNormals];
        // A lane without a hit may hold anything in u and v (Embree writes hits only); it reads the zero record.
        const float hu = h.u[i], hv = h.v[i];  // read unconditionally: plain SIMD loads
        const float u = found ? hu : 0.f, v = found ? hv : 0.f, w = 1.f - u - v;
        hits.px[i] = ((tri.p0.x * w) + (tri.p1.x * u)) + (tri.p2.x * v);
        hits.py[i] = ((tri.p0.y * w) + (tri.p1.y * u)) + (tri.p2.y * v);
        hits.pz[i] = ((tri.p0.z * w) + (tri.p1.z * u)) + (tri.p2.z * v);
        hits.gx[i] = tri.ng.x; hits.gy[i] = tri.ng.y; hits.gz[i] = tri.ng.z;
        // The zero record (no hit, or an exact shape) bounds nothing: the scene's floor.
        hits.offsetFloor[i] = hitOffsetFloor(m_offsetFloor, tri.p0, tri.p1, tri.p2, w, u, v, tri.ng);
        const float nx = ((n3.n0.x * w) + (n3.n1.x * u)) + (n3.n2.x * v);
        const float ny = ((n3.n0.y * w) + (n3.n1.y * u)) + (n3.n2.y * v);
        const float nz = ((n3.n0.z * w) + (n3.n1.z * u)) + (n3.n2.z * v);
        const float len2 = nx * nx + ny * ny + nz * nz;
        const bool interpolated = isSmooth & (len2 > 0.f);
        const float len = std::sqrt(interpolated ? len2 : 1.f);
        hits.nx[i] = interpolated ? nx / len : tri.ng.x;
        hits.ny[i] = interpolated ? ny / len : tri.ng.y;
        hits.nz[i] = interpolated ? nz / len : tri.ng.z;
        hits.t[i] = found ? rh.ray.tfar[i] : 0.f;
        hits.geom[i] = found ? h.geomID[i] : 0;
        hits.prim[i] = found ? h.primID[i] : 0;
        hits.found[i] = found;
        spheres += found & !mesh & (h.geomID[i] < m_firstDisk);
        others += found & (h.geomID[i] >= m_firstDisk);
    }
    hits.emitterOf = m_emitterOf.data();
    if (spheres != 0) fillSphereHits(rh, hits);
    if (others != 0) fillDiskCylinderHits(rh, hits);
}

void EmbreeScene::diskCylinderHit(unsigned geom, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n) const {
    if (geom < m_firstCylinder)
        shapeHitPoint(m_disks[geom - m_firstDisk], o, d, t, p, n);
    else
        shapeHitPoint(m_cylinders[geom - m_firstCylinder], o, d, t, p, n);
}

void EmbreeScene::fillDiskCylinderHits(const RTCRayHit16 &rh, HitPacket &hits) const {
    for (int i = 0; i < kPacketSize; ++i) {
        if (!hits.found[i] || hits.geom[i] < m_firstDisk) continue;
        const double t = double(rh.ray.tfar[i]) + double(rh.hit.u[i]);  // Embree's t, refined by the callback
        Vec3f p, n;
        const Vec3f o{hits.ox[i], hits.oy[i], hits.oz[i]}, d{hits.dx[i], hits.dy[i], hits.dz[i]};
        diskCylinderHit(hits.geom[i], o, d, t, p, n);
        hits.px[i] = p.x; hits.py[i] = p.y; hits.pz[i] = p.z;
        hits.gx[i] = n.x; hits.gy[i] = n.y; hits.gz[i] = n.z;
        hits.nx[i] = n.x; hits.ny[i] = n.y; hits.nz[i] = n.z;
    }
}

// sphereHitPoint's arithmetic (the same bits) over the lanes on a sphere, in double SIMD; the other
// lanes compute on the first sphere and keep what they have.
MCVAL_HOT void EmbreeScene::fillSphereHits(const RTCRayHit16 &rh, HitPacket &hits) const {
    const uint32_t meshes = static_cast<uint32_t>(m_meshes.size());
    alignas(64) double cx[kPacketSize], cy[kPacketSize], cz[kPacketSize], r[kPacketSize], sign[kPacketSize];
    alignas(64) int onSphere[kPacketSize];
    for (int i = 0; i < kPacketSize; ++i) {
        onSphere[i] = hits.found[i] & (hits.geom[i] >= meshes) & (hits.geom[i] < m_firstDisk);
        const Sphere &s = m_spheres[onSphere[i] ? hits.geom[i] - meshes : 0];
        cx[i] = s.center.x; cy[i] = s.center.y; cz[i] = s.center.z;
        r[i] = s.radius;
        sign[i] = s.flipNormals ? -1.0 : 1.0;
    }
    for (int i = 0; i < kPacketSize; ++i) {
        const double t = double(rh.ray.tfar[i]) + double(rh.hit.u[i]);  // Embree's t, refined by the callback
        const double vx = hits.ox[i] + t * hits.dx[i] - cx[i];
        const double vy = hits.oy[i] + t * hits.dy[i] - cy[i];
        const double vz = hits.oz[i] + t * hits.dz[i] - cz[i];
        const double len = std::sqrt(vx * vx + vy * vy + vz * vz);
        // Operands selected, never results: GCC will not if-convert a division in one arm of a ?:.
        const bool ok = len > 0.0;
        const double l = ok ? len : 1.0;
        const double qx = vx / l, qy = vy / l, qz = vz / l;
        const double ux = ok ? qx : 0.0, uy = ok ? qy : 0.0, uz = ok ? qz : 1.0;
        const float px = float(cx[i] + r[i] * ux), py = float(cy[i] + r[i] * uy), pz = float(cz[i] + r[i] * uz);
        const float nx = float(sign[i] * ux), ny = float(sign[i] * uy), nz = float(sign[i] * uz);
        const bool s = onSphere[i];
        hits.px[i] = s ? px : hits.px[i]; hits.py[i] = s ? py : hits.py[i]; hits.pz[i] = s ? pz : hits.pz[i];
        hits.gx[i] = s ? nx : hits.gx[i]; hits.gy[i] = s ? ny : hits.gy[i]; hits.gz[i] = s ? nz : hits.gz[i];
        hits.nx[i] = s ? nx : hits.nx[i]; hits.ny[i] = s ? ny : hits.ny[i]; hits.nz[i] = s ? nz : hits.nz[i];
    }
}

bool EmbreeScene::intersect(const Ray &ray, Hit &hit) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = toRtc(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_scene, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

    fillHit(ray, rh.hit.geomID, rh.hit.primID, rh.hit.u, rh.hit.v, rh.ray.tfar, hit);
    return true;
}

bool EmbreeScene::occluded(const Ray &ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = toRtc(ray);
    rtcOccluded1(m_scene, &context, &r);
    return r.tfar < 0.f;  // Embree sets tfar to -inf on a hit
}

OcclusionPacket::OcclusionPacket() {
    for (int i = 0; i < kPacketSize; ++i) {
        setFixedFields(rays, i);
        valid[i] = 0;
    }
}

RayHitPacket::RayHitPacket() {
    for (int i = 0; i < kPacketSize; ++i) {
        setFixedFields(rh.ray, i);
        rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        valid[i] = 0;
    }
}

MCVAL_HOT void EmbreeScene::intersect(RayHitPacket &packet, int count, HitPacket &hits) const {
    MCR_ASSERT(count > 0 && count <= kPacketSize);
    const RTCRay16 &r = packet.rh.ray;
    for (int i = 0; i < kPacketSize; ++i) {  // the rays as set, before the trace shortens tfar
        hits.ox[i] = r.org_x[i]; hits.oy[i] = r.org_y[i]; hits.oz[i] = r.org_z[i];
        hits.dx[i] = r.dir_x[i]; hits.dy[i] = r.dir_y[i]; hits.dz[i] = r.dir_z[i];
        hits.tnear[i] = r.tnear[i];
        hits.tfar[i] = r.tfar[i];
        if (!packet.valid[i]) setEmptyRay(packet.rh.ray, i);
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect16(packet.valid, m_scene, &context, &packet.rh);
    fillHits(packet.rh, count, hits);
}

MCVAL_HOT void EmbreeScene::intersect(RayHitPacket *packets, const int *counts, int n, HitPacket *hits) const {
    for (int j = 0; j < n; ++j) {
        MCR_ASSERT(counts[j] > 0 && counts[j] <= kPacketSize);
        RTCRay16 &r = packets[j].rh.ray;
        HitPacket &h = hits[j];
        for (int i = 0; i < kPacketSize; ++i) {  // the rays as set, before the trace shortens tfar
            h.ox[i] = r.org_x[i]; h.oy[i] = r.org_y[i]; h.oz[i] = r.org_z[i];
            h.dx[i] = r.dir_x[i]; h.dy[i] = r.dir_y[i]; h.dz[i] = r.dir_z[i];
            h.tnear[i] = r.tnear[i];
            h.tfar[i] = r.tfar[i];
            // A stream has no valid mask: a lane is left out by an empty interval.
            if (!packets[j].valid[i]) {
                setEmptyRay(r, i);
                r.tnear[i] = 1.f;
            }
        }
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersectNM(m_scene, &context, reinterpret_cast<RTCRayHitN *>(packets), kPacketSize, static_cast<unsigned>(n),
                   sizeof(RayHitPacket));
    for (int j = 0; j < n; ++j) fillHits(packets[j].rh, counts[j], hits[j]);
}

void EmbreeScene::occluded(OcclusionPacket &packet, bool coherent) const {
    if (packet.active == 0) return;
    for (int i = 0; i < kPacketSize; ++i)
        if (!packet.valid[i]) setEmptyRay(packet.rays, i);
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

}  // namespace mcval
