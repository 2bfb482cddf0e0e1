// The scene's triangle meshes and exact shapes (spheres, disks, cylinders) in one Embree 3 BVH, behind a small RAII class.
#pragma once

#include <vector>

#include <embree3/rtcore.h>

#include "bsdfs/textured_bsdf.h"
#include "hit_packet.h"
#include "ray.h"
#include "scene.h"

namespace mcval {

/// Up to kPacketSize occlusion rays in Embree's SoA layout, written lane by lane where they are made
/// (no Ray structs copied in between: partial writes read back whole stall the store buffer).
struct OcclusionPacket {
    alignas(64) RTCRay16 rays;
    alignas(64) int valid[kPacketSize];
    int active = 0;  ///< lanes set since clear()

    OcclusionPacket();  ///< the fields set() leaves alone, once
    void clear() {
        for (int &v : valid) v = 0;
        active = 0;
    }
    /// Lane i: the ray from o along d over [0, tfar].
    void set(int i, const Vec3f &o, const Vec3f &d, float tfar) {
        rays.org_x[i] = o.x; rays.org_y[i] = o.y; rays.org_z[i] = o.z;
        rays.dir_x[i] = d.x; rays.dir_y[i] = d.y; rays.dir_z[i] = d.z;
        rays.tnear[i] = 0.f;
        rays.tfar[i] = tfar;
        valid[i] = -1;
        ++active;
    }
    /// After EmbreeScene::occluded: whether lane i's ray was set and is blocked.
    bool blocked(int i) const { return valid[i] != 0 && rays.tfar[i] < 0.f; }  // Embree sets tfar to -inf on a hit
};

/// Up to kPacketSize closest-hit rays in Embree's SoA layout, written lane by lane where they are
/// made (the camera's rays), with room for their hits.
struct RayHitPacket {
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[kPacketSize];

    RayHitPacket();  ///< the fields set() leaves alone, once
    /// Lane i: the ray o + t d over [tnear, tfar]; `on` false leaves the lane out of the trace.
    void set(int i, bool on, const Vec3f &o, const Vec3f &d, float tnear, float tfar) {
        rh.ray.org_x[i] = o.x; rh.ray.org_y[i] = o.y; rh.ray.org_z[i] = o.z;
        rh.ray.dir_x[i] = d.x; rh.ray.dir_y[i] = d.y; rh.ray.dir_z[i] = d.z;
        rh.ray.tnear[i] = tnear;
        rh.ray.tfar[i] = tfar;
        rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        valid[i] = on ? -1 : 0;
    }
};

class EmbreeScene {
public:
    /// Builds the BVH over all meshes and exact shapes; meshes and spheres must outlive this object
    /// (disks and cylinders are copied). Geometry ids are the meshes' indices, then the spheres', the
    /// disks' and the cylinders' after them. Shapes name their BSDF in `bsdfs` (an index past its end, as
    /// with none given: Mitsuba's default diffuse 0.5).
    explicit EmbreeScene(const std::vector<Mesh> &meshes, const std::vector<Sphere> &spheres = {},
                         const std::vector<Disk> &disks = {}, const std::vector<Cylinder> &cylinders = {},
                         const BsdfList &bsdfs = {});
    /// Temporary meshes would die before the scene that traces them.
    explicit EmbreeScene(std::vector<Mesh> &&meshes, const std::vector<Sphere> &spheres = {},
                         const std::vector<Disk> &disks = {}, const std::vector<Cylinder> &cylinders = {},
                         const BsdfList &bsdfs = {}) = delete;
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    /// Closest hit along the ray, with position and normals filled in.
    bool intersect(const Ray &ray, Hit &hit) const;
    /// Closest hits of up to kPacketSize rays traced as one packet (coherent rays, such as the
    /// samples of one pixel, traverse the BVH together); found[i] tells whether ray i hit.
    void intersect16(const Ray *rays, int count, Hit *hits, bool *found) const;
    /// Traces the first `count` lanes of `packet` (all set) and gives back, lane by lane, each ray as
    /// set and its hit (hits.found[i]; lanes past `count` have none).
    void intersect(RayHitPacket &packet, int count, HitPacket &hits) const;
    /// intersect() for `n` packets at once, traced as one coherent Embree stream (neighbouring packets
    /// traverse the BVH together): packet j's first counts[j] lanes, its hits into hits[j].
    void intersect(RayHitPacket *packets, const int *counts, int n, HitPacket *hits) const;
    /// Whether anything lies on the ray in [tnear, tfar].
    bool occluded(const Ray &ray) const;
    /// Traces the set lanes of `packet` (nothing if none); read the answers with packet.blocked(i).
    void occluded(OcclusionPacket &packet, bool coherent) const;

    /// The BSDF of geometry `geom` (Hit::geom), whatever the shape.
    const Bsdf &bsdf(uint32_t geom) const { return *m_bsdf[geom]; }
    /// The BSDF at the hit: bsdf(hit.geom), or for a textured one (a TexturedBsdf) the surface at the hit's
    /// (u, v), made in `scratch` (which must outlive its use).
    const Bsdf &bsdfAt(const Hit &hit, BsdfScratch &scratch) const;
    /// Mitsuba's (u, v) at a hit on a mesh with texture coordinates (Mesh::texcoords), interpolated by the
    /// barycentrics of hit.p; (0, 0) elsewhere (the loader gives textures only to such meshes).
    Vec2f uvAt(const Hit &hit) const;
    /// The Lambertian albedo of the front of geometry `geom` (its BSDF's lambertianAlbedo, 0 where that side
    /// is not Lambertian), in one flat table for the packet paths (simple, ao).
    const Color &reflectance(uint32_t geom) const { return m_reflectance[geom]; }
    /// Whether geometry `geom` is lit from behind too (Mitsuba's twosided bsdf), as a diffuse surface whose
    /// normal faces the ray; a one-sided one is black from behind.
    bool twoSided(uint32_t geom) const { return m_twoSided[geom] != 0; }
    /// The Lambertian albedo of the back of a two-sided geometry `geom` (black for a one-sided one).
    const Color &backReflectance(uint32_t geom) const { return m_backReflectance[geom]; }
    /// The area emitter of geometry `geom` (Hit::emitter): its index in SceneEmitters, whose list starts
    /// with the emitting shapes in geometry order; -1 for a shape that does not emit.
    int emitter(uint32_t geom) const { return m_emitterOf[geom]; }
    /// The table of emitter() by geometry id (HitPacket::emitterOf).
    const int *emitterTable() const { return m_emitterOf.data(); }

private:
    /// Position and normals of a hit: on triangle prim of a mesh at barycentrics (u, v), or on an
    /// exact shape at t + u (u holds what float32 rounded off t).
    void fillHit(const Ray &ray, unsigned geom, unsigned prim, float u, float v, float t, Hit &hit) const;

    /// The hits of a traced packet's first `count` lanes into `hits`: the triangles' in SIMD over all
    /// lanes (gathers from the flat tables below), then the lanes on an exact shape.
    void fillHits(const RTCRayHit16 &rh, int count, HitPacket &hits) const;
    /// fillHits' pass over the lanes on a sphere: their exact points and normals.
    void fillSphereHits(const RTCRayHit16 &rh, HitPacket &hits) const;
    /// fillHits' pass over the lanes on a disk or a cylinder, one lane at a time.
    void fillDiskCylinderHits(const RTCRayHit16 &rh, HitPacket &hits) const;
    /// The exact point and normal (geometric and shading alike) on disk or cylinder `geom`.
    void diskCylinderHit(unsigned geom, const Vec3f &o, const Vec3f &d, double t, Vec3f &p, Vec3f &n) const;

    /// A triangle as a hit reads it: its corners and unit face normal (computed once) in one record,
    /// so that the packet's hits can be gathered in SIMD rather than walked through index arrays.
    struct TriangleRecord {
        Vec3f p0, p1, p2, ng;
    };
    /// The vertex normals of a triangle of a smooth mesh (one with normals), likewise.
    struct TriangleNormals {
        Vec3f n0, n1, n2;
    };
    static constexpr uint32_t kFlat = ~0u;  ///< m_firstNormals of a mesh without normals

    const std::vector<Mesh> &m_meshes;
    const std::vector<Sphere> &m_spheres;
    std::vector<Disk> m_disks;          ///< copies: Embree holds pointers to them, so never resized
    std::vector<Cylinder> m_cylinders;
    uint32_t m_firstDisk = 0, m_firstCylinder = 0;  ///< their first geometry ids
    /// Adds the next geometry id's BSDF (bsdfs[index], the default past its end) and its emitter index (-1 if
    /// it does not emit).
    void addMaterial(const BsdfList &bsdfs, uint32_t index, bool emits);

    std::vector<std::shared_ptr<const Bsdf>> m_bsdf;  ///< by geometry id
    std::vector<const TexturedBsdf *> m_textured;  ///< by geometry id: its BSDF if textured, else null
    std::vector<Color> m_reflectance;  ///< by geometry id: one table whatever the shape
    std::vector<Color> m_backReflectance;
    std::vector<uint8_t> m_twoSided;
    std::vector<int> m_emitterOf;      ///< by geometry id: emitter()
    int m_areaEmitters = 0;            ///< emitting shapes so far
    /// Every mesh's triangles, then a zero record that lanes without a triangle read harmlessly.
    std::vector<TriangleRecord> m_triangles;
    std::vector<TriangleNormals> m_normals;            ///< the smooth meshes' triangles, then a zero record
    std::vector<uint32_t> m_firstTriangle, m_firstNormals;  ///< by mesh: where its records start
    float m_offsetFloor = 0.f;         ///< Hit::offsetFloor: from the scene's smallest shape
    RTCDevice m_device = nullptr;
    RTCScene m_scene = nullptr;
};

}  // namespace mcval
