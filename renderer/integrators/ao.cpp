#include "ao.h"

#include "../frame.h"
#include "../warp.h"

namespace mcval {

AoIntegrator::AoIntegrator(const SceneDescription &scene, const EmbreeScene &embree, int samples)
    : m_embree(embree), m_environment(scene.environment.value_or(Color(1.f, 1.f, 1.f))), m_samples(samples) {}

Color AoIntegrator::Li(const Ray &ray, const Hit *camHit, Sampler &sampler, RayCounts &counts) const {
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
    const Color &rho = m_embree.meshes()[hit.mesh].reflectance;
    return rho * m_environment * (static_cast<float>(visible) / static_cast<float>(m_samples));
}

}  // namespace mcval
