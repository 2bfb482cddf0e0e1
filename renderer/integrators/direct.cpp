// direct: Mitsuba 3's direct illumination integrator (src/integrators/direct.cpp). At the first hit, light
// from every emitter by `emitter_samples` emitter samples and `bsdf_samples` BSDF samples, combined by
// multiple importance sampling with the power heuristic; the camera ray sees the emitter it hits unless
// hide_emitters, which lets it pass through area emitters (Mitsuba's skip_area_emitters).
#include <cmath>
#include <limits>

#include "../emitters/scene_emitters.h"
#include "../frame.h"
#include "../xml_props.h"
#include "hidden_emitters.h"
#include "mis.h"
#include "registry.h"

namespace mcval {

namespace {

/// The most samples of each strategy per camera sample.
constexpr int kMaxShadingSamples = 1024;

class DirectIntegrator final : public Integrator {
public:
    DirectIntegrator(const SceneDescription &scene, const EmbreeScene &embree, int emitterSamples, int bsdfSamples)
        : m_embree(embree), m_emitters(scene), m_hideEmitters(scene.hideEmitters.value_or(false)),
          m_emitterSamples(emitterSamples), m_bsdfSamples(bsdfSamples),
          m_weightBsdf(1.f / float(bsdfSamples)), m_weightLum(1.f / float(emitterSamples)),
          m_fracBsdf(float(bsdfSamples) / float(emitterSamples + bsdfSamples)),
          m_fracLum(float(emitterSamples) / float(emitterSamples + bsdfSamples)) {}

    Color Li(const Ray &ray, const Hit *first, Sampler &sampler, RayCounts &counts) const override {
        Color result(0.f, 0.f, 0.f);
        Hit hit;
        bool found = first != nullptr;
        if (found) hit = *first;
        if (m_hideEmitters) {
            found = skipAreaEmitters(m_embree, ray.d, hit, found, counts);
        } else {
            result = result + visible(ray.d, found ? &hit : nullptr);
        }
        if (!found) return result;

        const Frame frame(hit.ns);
        const Vec3f wi = toLocal(frame, -ray.d);
        BsdfScratch textured;
        const Bsdf &bsdf = m_embree.bsdfAt(hit, textured);
        const EmitterSampler &choose = m_emitters.sampler();

        // Emitter sampling.
        for (int i = 0; i < m_emitterSamples; ++i) {
            const Vec2f u = sampler.next2D();
            const EmitterSampler::Choice c = choose.sample(u.x);
            if (c.index < 0) continue;
            EmitterSample s = m_emitters[size_t(c.index)].sample(hit.p, {c.reused, u.y});
            if (!(s.pdf > 0.f) || (s.weight.x == 0.f && s.weight.y == 0.f && s.weight.z == 0.f)) continue;
            s.pdf *= c.pmf;
            s.weight = s.weight / c.pmf;
            const Vec3f wo = toLocal(frame, s.d);
            const Color f = bsdf.eval(wi, wo);
            if (passesNothing(f, s.weight)) continue;
            // Toward a point: aimed from the offset origin, stopping just short of the emitter (nothing behind
            // it may shadow); toward an infinitely far emitter, to the end.
            const Ray shadow = std::isfinite(s.dist) ? spawnRayTo(hit, s.p)
                                                     : spawnRay(hit, s.d, std::numeric_limits<float>::infinity());
            counts.shadow += 1;
            if (m_embree.occluded(shadow)) continue;
            const float bsdfPdf = bsdf.pdf(wi, wo);
            // A delta light takes the whole weight (no BSDF sample can find it), over the samples drawn.
            const float mis = (s.delta ? 1.f : misWeight(s.pdf * m_fracLum, bsdfPdf * m_fracBsdf)) * m_weightLum;
            result = result + f * s.weight * mis;
        }

        // BSDF sampling.
        for (int i = 0; i < m_bsdfSamples; ++i) {
            const Vec2f u = sampler.next2D();
            const BsdfSample bs = bsdf.sample(wi, u, sampler.next2D().x);
            if (bs.weight.x == 0.f && bs.weight.y == 0.f && bs.weight.z == 0.f) continue;
            const Vec3f d = frame.toWorld(bs.wo);
            Hit next;
            counts.shadow += 1;
            const bool hitSomething = m_embree.intersect(spawnRay(hit, d, 1e30f), next);
            const int index = hitSomething ? next.emitter : m_emitters.environment();
            if (index < 0) continue;
            const EmitterHit at = hitSomething ? emitterHit(next, d) : escaped(d);
            const Emitter &emitter = m_emitters[size_t(index)];
            // A delta lobe (a mirror's, a glass's; its pdf infinite) takes the whole weight: no emitter sample
            // can find its direction (Mitsuba gives the emitter's pdf 0 there), and inf / inf would make it 0.
            const float mis = std::isinf(bs.pdf)
                                  ? 1.f
                                  : misWeight(bs.pdf * m_fracBsdf, emitter.pdf(hit.p, at) * choose.pmf(index) * m_fracLum);
            result = result + bs.weight * emitter.eval(at) * (mis * m_weightBsdf);
        }
        return result;
    }

private:
    /// What the camera sees of an emitter along d: the area emitter it hit, or the environment if it escaped.
    Color visible(const Vec3f &d, const Hit *hit) const {
        if (hit) return hit->emitter >= 0 ? m_emitters[size_t(hit->emitter)].eval(emitterHit(*hit, d)) : Color();
        const int env = m_emitters.environment();
        return env >= 0 ? m_emitters[size_t(env)].eval(escaped(d)) : Color(0.f, 0.f, 0.f);
    }

    const EmbreeScene &m_embree;
    SceneEmitters m_emitters;
    bool m_hideEmitters;
    int m_emitterSamples, m_bsdfSamples;
    float m_weightBsdf, m_weightLum, m_fracBsdf, m_fracLum;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "direct",
    "direct illumination from every emitter, emitter and BSDF samples with MIS (properties: emitter_samples, "
    "bsdf_samples, shading_samples = 1, hide_emitters = false)",
    SceneUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds::all(), /*readsReflectance=*/true,
             /*readsAnyBsdf=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        int emitterSamples = 1, bsdfSamples = 1;
        if (props) {
            // Mitsuba: shading_samples sets both, and cannot be given with either.
            if (props->has("shading_samples") && (props->has("emitter_samples") || props->has("bsdf_samples")))
                props->failAt("shading_samples", "give shading_samples (both counts) or emitter_samples and "
                                                 "bsdf_samples, not both, as Mitsuba");
            const int shading = props->getInt("shading_samples", 1);
            props->requireRange("shading_samples", shading, 0, kMaxShadingSamples);
            emitterSamples = props->getInt("emitter_samples", shading);
            props->requireRange("emitter_samples", emitterSamples, 0, kMaxShadingSamples);
            bsdfSamples = props->getInt("bsdf_samples", shading);
            props->requireRange("bsdf_samples", bsdfSamples, 0, kMaxShadingSamples);
            props->ignore("hide_emitters");  // read by the loader for every integrator type (scene.h)
            props->finish("emitter_samples, bsdf_samples, shading_samples, hide_emitters");
            if (emitterSamples + bsdfSamples == 0)
                props->failAt("emitter_samples", "direct needs at least one emitter or BSDF sample");
        }
        return [emitterSamples, bsdfSamples](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<DirectIntegrator>(scene, embree, emitterSamples, bsdfSamples);
        };
    },
});

}  // namespace mcval
