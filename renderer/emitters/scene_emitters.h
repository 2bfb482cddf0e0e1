// The emitters of a scene as models (emitter.h), in one list an integrator indexes: the area emitters
// first, in Embree's geometry order (so that Hit::emitter indexes this list), then the point, spot and
// directional lights and the environment (constant or envmap).
#pragma once

#include <memory>
#include <vector>

#include "../ray.h"
#include "emitter.h"
#include "emitter_sampler.h"

namespace mcval {

class SceneEmitters {
public:
    /// The models of the scene's emitters; the scene must outlive this object (area emitters sample its shapes).
    explicit SceneEmitters(const SceneDescription &scene);
    size_t size() const { return m_emitters.size(); }
    const Emitter &operator[](size_t i) const { return *m_emitters[i]; }
    /// The index of the environment (constant or envmap), which rays that escape the scene reach, or -1.
    int environment() const { return m_environment; }
    /// How a light sample chooses its emitter.
    const EmitterSampler &sampler() const { return m_sampler; }

private:
    std::vector<std::unique_ptr<Emitter>> m_emitters;
    int m_environment = -1;
    EmitterSampler m_sampler;
};

/// Where a ray reached an emitter's surface, for Emitter::eval and pdf: the hit's point
/// and normals, and the ray's unit direction and length.
inline EmitterHit emitterHit(const Hit &hit, const Vec3f &d) { return {hit.p, hit.ng, hit.ns, d, hit.t}; }
/// A ray along unit d that left the scene, for the environment's eval and pdf.
inline EmitterHit escaped(const Vec3f &d) { return {{}, {}, {}, d}; }

}  // namespace mcval
