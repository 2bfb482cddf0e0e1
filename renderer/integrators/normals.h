#pragma once

#include "integrator.h"

namespace mcval {

/// Shading normal at the first hit; 0 where the ray escapes.
class NormalsIntegrator final : public Integrator {
public:
    NormalsIntegrator() = default;
    Color Li(const Ray &ray, const Hit *hit, Sampler &sampler, RayCounts &counts) const override;
};

}  // namespace mcval
