// normals: the shading normal at the first hit, as Mitsuba's aov "nn:sh_normal". Deterministic
// per ray, so it checks camera and geometry before any noise enters.
#include "normals.h"

namespace mcr {

Color NormalsIntegrator::Li(const Ray &ray, Sampler &, RayCounts &counts) const {
    Hit hit;
    if (!traceCamera(m_embree, ray, hit, counts)) return {0.f, 0.f, 0.f};
    return hit.ns;
}

}  // namespace mcr
