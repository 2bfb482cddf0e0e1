// The scene's triangles in one Embree 3 BVH, behind a small RAII class.
#pragma once

#include <vector>

#include <embree3/rtcore.h>

#include "ray.h"
#include "scene.h"

namespace mcval {

class EmbreeScene {
public:
    /// Builds the BVH over all meshes; they must outlive this object.
    explicit EmbreeScene(const std::vector<Mesh> &meshes);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    /// Closest hit along the ray, with position and normals filled in.
    bool intersect(const Ray &ray, Hit &hit) const;
    /// Closest hits of up to 8 rays traced as one packet (coherent rays, such as the samples of
    /// one pixel, traverse the BVH together); found[i] tells whether ray i hit.
    void intersect8(const Ray *rays, int count, Hit *hits, bool *found) const;
    /// Whether anything lies on the ray in [tnear, tfar].
    bool occluded(const Ray &ray) const;

    const std::vector<Mesh> &meshes() const { return m_meshes; }

private:
    /// Position and normals of a hit on triangle prim of mesh geom at barycentrics (u, v).
    void fillHit(unsigned geom, unsigned prim, float u, float v, float t, Hit &hit) const;

    const std::vector<Mesh> &m_meshes;
    RTCDevice m_device = nullptr;
    RTCScene m_scene = nullptr;
};

}  // namespace mcval
