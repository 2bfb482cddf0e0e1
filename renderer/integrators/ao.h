#pragma once

#include "integrator.h"

namespace mcval {

/// Ambient occlusion under the constant emitter (radiance 1 without one), cosine-weighted:
/// L = rho * L_env * mean(V(w_i)) over `samples` occlusion rays per camera sample.
class AoIntegrator final : public Integrator {
public:
    AoIntegrator(const SceneDescription &scene, const EmbreeScene &embree, int samples);
    Color Li(const Ray &ray, const Hit *hit, Sampler &sampler, RayCounts &counts) const override;

private:
    const EmbreeScene &m_embree;
    Color m_environment;
    int m_samples;
};

}  // namespace mcval
