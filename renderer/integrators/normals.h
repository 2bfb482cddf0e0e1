#pragma once

#include "integrator.h"

namespace mcr {

/// Shading normal at the first hit; 0 where the ray escapes.
class NormalsIntegrator final : public Integrator {
public:
    explicit NormalsIntegrator(const EmbreeScene &embree) : m_embree(embree) {}
    Color Li(const Ray &ray, Sampler &sampler, RayCounts &counts) const override;

private:
    const EmbreeScene &m_embree;
};

}  // namespace mcr
