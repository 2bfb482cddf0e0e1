// ao_uniform (test build only): ambient occlusion with directions drawn uniformly on the hemisphere and
// weighted by 2 cos, the seed document's estimator. Its mean is ao's, its variance larger (an unoccluded
// point: L^2 / 3 where ao's is 0), so every test of the mean passes it: the known-wrong twin of the
// variance test (tests/images/test_variance_twin.py).
#include "frame.h"
#include "warp.h"
#include "integrators/registry.h"
#include "xml_props.h"

namespace mcval {

namespace {

class AoUniformIntegrator final : public Integrator {
public:
    AoUniformIntegrator(const SceneDescription &scene, const EmbreeScene &embree)
        : m_embree(embree), m_environment(scene.environment.value_or(Color(1.f, 1.f, 1.f))),
          m_background(scene.hideEmitters.value_or(true) ? Color(0.f, 0.f, 0.f) : m_environment) {}

    Color Li(const Ray &ray, const Hit *hit, Sampler &sampler, RayCounts &counts) const override {
        if (!hit) return m_background;
        const Vec3f &n = hit->ns;
        if (!(n.x * ray.d.x + n.y * ray.d.y + n.z * ray.d.z < 0.f)) return Color(0.f, 0.f, 0.f);  // a back face
        const Vec3f local = squareToUniformHemisphere(sampler.next2D());
        const Vec3f wi = Frame(n).toWorld(local);
        counts.shadow += 1;
        if (m_embree.occluded(spawnRay(*hit, wi, 1e30f))) return Color(0.f, 0.f, 0.f);
        // ao's white surface: f cos / pdf = (1 / pi) cos / (1 / (2 pi)) = 2 cos.
        return m_environment * (2.f * local.z);
    }

private:
    const EmbreeScene &m_embree;
    Color m_environment, m_background;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "ao_uniform",
    "ambient occlusion sampled uniformly on the hemisphere, weighted by 2 cos (test build only)",
    SceneUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds{EmitterKind::Constant}, /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        if (props) {
            props->ignore("hide_emitters");
            props->finish("no properties");
        }
        return [](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<AoUniformIntegrator>(scene, embree);
        };
    },
});

}  // namespace mcval
