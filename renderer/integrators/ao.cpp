// ao: ambient occlusion under the constant emitter (radiance 1 without one), cosine-weighted:
// L = rho * L_env * mean(V(w_i)) over `samples` occlusion rays per camera sample.
#include "../frame.h"
#include "../scene_limits.h"
#include "../warp.h"
#include "../xml_props.h"
#include "registry.h"

namespace mcval {

namespace {

class AoIntegrator final : public Integrator {
public:
    AoIntegrator(const SceneDescription &scene, const EmbreeScene &embree, int samples)
        : m_embree(embree), m_environment(scene.environment.value_or(Color(1.f, 1.f, 1.f))), m_samples(samples) {}

    Color Li(const Ray &ray, const Hit *camHit, Sampler &sampler, RayCounts &counts) const override {
        // A camera ray that escapes returns 0 (the environment itself is hidden); so does a back face.
        if (!camHit || dot(camHit->ns, ray.d) >= 0.f) return {0.f, 0.f, 0.f};
        const Hit &hit = *camHit;
        const Frame frame(hit.ns);
        int visible = 0;
        for (int i = 0; i < m_samples; ++i) {
            // Cosine-weighted sampling cancels the cosine over its pdf: each unoccluded ray counts rho * L_env.
            const Vec3f wi = frame.toWorld(squareToCosineHemisphere(sampler.next2D()));
            ++counts.shadow;
            if (!m_embree.occluded(spawnRay(hit, wi, 1e30f))) ++visible;
        }
        const Color &rho = m_embree.reflectance(hit.geom);
        return rho * m_environment * (static_cast<float>(visible) / static_cast<float>(m_samples));
    }

private:
    const EmbreeScene &m_embree;
    Color m_environment;
    int m_samples;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "ao",
    "ambient occlusion under the constant emitter, cosine-weighted (property: samples)",
    SceneUse{/*needsPointLight=*/false, /*areaEmittersLight=*/false, /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        int samples = 1;
        if (props) {
            samples = props->getInt("samples", 1);
            props->requireRange("samples", samples, 1, kMaxAoSamples);
            props->finish("samples");
        }
        return [samples](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<AoIntegrator>(scene, embree, samples);
        };
    },
});

}  // namespace mcval
