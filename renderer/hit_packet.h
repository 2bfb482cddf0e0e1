// The first hits of a packet of camera rays in SoA form (one array per field, lane i of each), as
// Embree answers them and as the integrators' SIMD loops read them: no Hit structs in between.
#pragma once

#include <cstdint>

#include "ray.h"

namespace mcval {

struct HitPacket {
    // The camera rays as traced (tfar before the trace).
    alignas(64) float ox[kPacketSize], oy[kPacketSize], oz[kPacketSize];
    alignas(64) float dx[kPacketSize], dy[kPacketSize], dz[kPacketSize];
    alignas(64) float tnear[kPacketSize], tfar[kPacketSize];
    // Their hits, where found[i]; a lane without one holds zeros (never garbage), so that loops over
    // all kPacketSize lanes stay finite and deterministic.
    alignas(64) float t[kPacketSize];
    alignas(64) float px[kPacketSize], py[kPacketSize], pz[kPacketSize];     ///< Hit::p
    alignas(64) float gx[kPacketSize], gy[kPacketSize], gz[kPacketSize];     ///< Hit::ng
    alignas(64) float nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];     ///< Hit::ns
    alignas(64) uint32_t geom[kPacketSize], prim[kPacketSize];
    alignas(64) int found[kPacketSize];
    alignas(64) float offsetFloor[kPacketSize];  ///< Hit::offsetFloor: the scene's, or a triangle hit's own bound
    /// Hit::emitter by geometry id (the scene's table, which its trace sets), read by hit(i) only: the SIMD
    /// loops that do not ask for emitters pay nothing for them. nullptr: the lanes' own, as setHit gave them.
    const int *emitterOf = nullptr;
    alignas(64) int emitter[kPacketSize];  ///< Hit::emitter of lanes set by setHit (where emitterOf is nullptr)

    Ray ray(int i) const {
        Ray r;
        r.o = {ox[i], oy[i], oz[i]};
        r.d = {dx[i], dy[i], dz[i]};
        r.tnear = tnear[i];
        r.tfar = tfar[i];
        return r;
    }
    Hit hit(int i) const {
        Hit h;
        h.t = t[i];
        h.p = {px[i], py[i], pz[i]};
        h.ng = {gx[i], gy[i], gz[i]};
        h.ns = {nx[i], ny[i], nz[i]};
        h.geom = geom[i];
        h.prim = prim[i];
        h.offsetFloor = offsetFloor[i];
        h.emitter = !found[i] ? -1 : emitterOf ? emitterOf[geom[i]] : emitter[i];
        return h;
    }
    void setRay(int i, const Ray &r) {
        ox[i] = r.o.x; oy[i] = r.o.y; oz[i] = r.o.z;
        dx[i] = r.d.x; dy[i] = r.d.y; dz[i] = r.d.z;
        tnear[i] = r.tnear;
        tfar[i] = r.tfar;
    }
    /// Lane i's hit, its emitter included (for a packet whose emitterOf is nullptr, as one built by hand).
    void setHit(int i, const Hit &h) {
        t[i] = h.t;
        px[i] = h.p.x; py[i] = h.p.y; pz[i] = h.p.z;
        gx[i] = h.ng.x; gy[i] = h.ng.y; gz[i] = h.ng.z;
        nx[i] = h.ns.x; ny[i] = h.ns.y; nz[i] = h.ns.z;
        geom[i] = h.geom;
        prim[i] = h.prim;
        offsetFloor[i] = h.offsetFloor;
        emitter[i] = h.emitter;
        found[i] = 1;
    }
    /// Lane i without a hit: zeros.
    void clearHit(int i) {
        t[i] = px[i] = py[i] = pz[i] = gx[i] = gy[i] = gz[i] = nx[i] = ny[i] = nz[i] = offsetFloor[i] = 0.f;
        geom[i] = prim[i] = 0;
        emitter[i] = -1;
        found[i] = 0;
    }
    /// Whether lane i hit the front of its surface (the side its shading normal points to): one-sided
    /// diffuse surfaces, as Mitsuba's, are black from behind.
    bool front(int i) const { return (found[i] != 0) & (nx[i] * dx[i] + ny[i] * dy[i] + nz[i] * dz[i] < 0.f); }
    /// The origin of a ray leaving lane i's hit toward d (ray.h's spawnOrigin).
    Vec3f spawnOrigin(int i, const Vec3f &d) const {
        return mcval::spawnOrigin({px[i], py[i], pz[i]}, {gx[i], gy[i], gz[i]}, offsetFloor[i], d);
    }
};

}  // namespace mcval
