// normals: the shading normal at the first hit, as Mitsuba's aov "nn:sh_normal". Deterministic
// per ray, so it checks camera and geometry before any noise enters.
#include "normals.h"

namespace mcval {

Color NormalsIntegrator::Li(const Ray &, const Hit *hit, Sampler &, RayCounts &) const {
    return hit ? hit->ns : Color(0.f, 0.f, 0.f);
}

}  // namespace mcval
