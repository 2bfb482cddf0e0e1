// simple: direct light from point emitters on diffuse surfaces, with shadow rays (Nori's simple
// integrator): L = (rho / pi) * I * max(0, cos) / r^2 * V, summed over the point lights.
#include <cmath>

#include "../warp.h"
#include "../xml_props.h"
#include "registry.h"

namespace mcval {

namespace {

class SimpleIntegrator final : public Integrator {
public:
    SimpleIntegrator(const SceneDescription &scene, const EmbreeScene &embree) : m_scene(scene), m_embree(embree) {}

    Color Li(const Ray &ray, const Hit *camHit, Sampler &, RayCounts &counts) const override {
        // One-sided diffuse, as Mitsuba's: black seen from behind the shading normal.
        if (!camHit || dot(camHit->ns, ray.d) >= 0.f) return {0.f, 0.f, 0.f};
        const Hit &hit = *camHit;
        const Color &rho = m_embree.reflectance(hit.geom);
        Color sum{0.f, 0.f, 0.f};
        for (const PointLight &light : m_scene.pointLights) {
            const Vec3f toLight = light.position - hit.p;
            const float dist2 = squaredNorm(toLight);
            if (!(dist2 > 0.f)) continue;
            const float dist = std::sqrt(dist2);
            const Vec3f wi = toLight / dist;
            const float cosTheta = dot(hit.ns, wi);
            if (cosTheta <= 0.f) continue;
            // Stop just short of the light: nothing behind it may shadow.
            const Ray shadow = spawnRay(hit, wi, dist * (1.f - 1e-4f));
            ++counts.shadow;
            if (m_embree.occluded(shadow)) continue;
            sum = sum + light.intensity * (cosTheta / dist2);
        }
        return rho * sum * kInvPi;
    }

private:
    const SceneDescription &m_scene;
    const EmbreeScene &m_embree;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "simple",
    "point lights on diffuse surfaces, with shadow rays",
    SceneUse{/*needsPointLight=*/true, /*areaEmittersLight=*/true, /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        if (props) props->finish("no properties");
        return [](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<SimpleIntegrator>(scene, embree);
        };
    },
});

}  // namespace mcval
