// The scene's triangles in one Embree 3 BVH, behind a small RAII class.
#pragma once

#include <vector>

#include <embree3/rtcore.h>

#include "ray.h"
#include "scene.h"

namespace mcr {

class EmbreeScene {
public:
    /// Builds the BVH over all meshes; they must outlive this object.
    explicit EmbreeScene(const std::vector<Mesh> &meshes);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene &) = delete;
    EmbreeScene &operator=(const EmbreeScene &) = delete;

    /// Closest hit along the ray, with position and normals filled in.
    bool intersect(const Ray &ray, Hit &hit) const;
    /// Whether anything lies on the ray in [tnear, tfar].
    bool occluded(const Ray &ray) const;

    const std::vector<Mesh> &meshes() const { return m_meshes; }

private:
    const std::vector<Mesh> &m_meshes;
    RTCDevice m_device = nullptr;
    RTCScene m_scene = nullptr;
};

}  // namespace mcr
