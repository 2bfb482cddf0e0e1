// path: Mitsuba 3's path tracer (src/integrators/path.cpp). At each vertex, the emission the path reaches, then
// one emitter sample (next-event estimation) and one BSDF sample that continues the path, the two combined by
// multiple importance sampling with the power heuristic; Russian roulette from the rr_depth-th bounce on.
// max_depth counts vertices as Mitsuba does: 1 sees emitters only, 2 is direct light, -1 has no limit; the
// camera ray of hide_emitters passes through emitting surfaces (no vertex) and sees no environment.
//
// `strategy` (mcval's own property; Mitsuba's path is "mis") selects the estimator of the light that reaches
// each vertex, as Nori's path_ems, path_mats and path_mis: "ems" takes it from emitter samples alone (a BSDF
// sample's emission counts only after a delta lobe, which no emitter sample finds), "mats" from BSDF samples
// alone, "mis" from both. All three estimate one image where no light is a delta light.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "../emitters/scene_emitters.h"
#include "../frame.h"
#include "../xml_props.h"
#include "hidden_emitters.h"
#include "mis.h"
#include "registry.h"

namespace mcval {

namespace {

enum class Strategy { Ems, Mats, Mis };

/// The most vertices max_depth may ask for (-1: unlimited, which Russian roulette ends).
constexpr int kMaxDepth = 1 << 20;
/// Russian roulette's highest survival probability, so that a path of full throughput ends too (Mitsuba's).
constexpr float kMaxSurvival = 0.95f;

float maxComponent(const Color &c) { return std::max(c.x, std::max(c.y, c.z)); }

class PathIntegrator final : public Integrator {
public:
    PathIntegrator(const SceneDescription &scene, const EmbreeScene &embree, uint32_t maxDepth, uint32_t rrDepth,
                   Strategy strategy)
        : m_embree(embree), m_emitters(scene), m_hideEmitters(scene.hideEmitters.value_or(false)),
          m_maxDepth(maxDepth), m_rrDepth(rrDepth), m_strategy(strategy) {}

    Color Li(const Ray &cameraRay, const Hit *first, Sampler &sampler, RayCounts &counts) const override {
        Color result(0.f, 0.f, 0.f), throughput(1.f, 1.f, 1.f);
        if (m_maxDepth == 0) return result;
        const EmitterSampler &choose = m_emitters.sampler();
        Ray ray = cameraRay;
        Hit hit;
        bool found = first != nullptr;
        if (found) hit = *first;
        if (m_hideEmitters) found = skipAreaEmitters(m_embree, ray.d, hit, found, counts);
        // The vertex the current ray left and how its direction was drawn: the camera's counts as a delta lobe
        // (no emitter sample could have found what it sees).
        Vec3f prevP;
        float prevPdf = 1.f;
        // The relative index of refraction the path has crossed: the radiance scale (1 / eta^2) it carries.
        float eta = 1.f;
        bool prevDelta = true;

        for (uint32_t depth = 0;; ++depth) {
            // Emission the path reached, weighted against the emitter sample that could have found it.
            const int index = found ? hit.emitter : m_emitters.environment();
            if (index >= 0 && !(depth == 0 && m_hideEmitters)) {
                const EmitterHit at = found ? emitterHit(hit, ray.d) : escaped(ray.d);
                const Emitter &emitter = m_emitters[size_t(index)];
                float weight = 1.f;
                if (!prevDelta && m_strategy == Strategy::Ems) weight = 0.f;
                else if (!prevDelta && m_strategy == Strategy::Mis)
                    weight = misWeight(prevPdf, emitter.pdf(prevP, at) * choose.pmf(index));
                if (weight > 0.f) result = result + throughput * emitter.eval(at) * weight;
            }
            if (!found || depth + 1 >= m_maxDepth) break;

            const Frame frame(hit.ns);
            const Vec3f wi = toLocal(frame, -ray.d);
            BsdfScratch textured;
            const Bsdf &bsdf = m_embree.bsdfAt(hit, textured);
            if (m_strategy != Strategy::Mats) result = result + throughput * emitterSample(hit, frame, wi, bsdf,
                                                                                          sampler, counts);

            // The BSDF sample that continues the path; `choice` picks Russian roulette's fate (x) and the lobe (y).
            const Vec2f u = sampler.next2D(), choice = sampler.next2D();
            const BsdfSample bs = bsdf.sample(wi, u, choice.y);
            throughput = throughput * bs.weight;
            if (!(maxComponent(throughput) > 0.f)) break;
            prevP = hit.p;
            prevPdf = bs.pdf;
            prevDelta = std::isinf(bs.pdf);
            eta *= bs.eta;
            const Vec3f d = frame.toWorld(bs.wo);

            // Russian roulette on the throughput without the radiance scale of refraction (Mitsuba's).
            if (depth + 1 >= m_rrDepth) {
                const float survival = std::min(maxComponent(throughput) * eta * eta, kMaxSurvival);
                if (!(choice.x < survival)) break;
                throughput = throughput / survival;
            }
            ray = spawnRay(hit, d, 1e30f);
            counts.shadow += 1;  // rays beyond the camera ray, as direct counts its BSDF rays
            found = m_embree.intersect(ray, hit);
        }
        return result;
    }

private:
    /// One emitter sample's light at `hit`, through the BSDF, MIS-weighted against the BSDF sample.
    Color emitterSample(const Hit &hit, const Frame &frame, const Vec3f &wi, const Bsdf &bsdf, Sampler &sampler,
                        RayCounts &counts) const {
        const Vec2f u = sampler.next2D();
        const EmitterSampler::Choice c = m_emitters.sampler().sample(u.x);
        if (c.index < 0) return {};
        EmitterSample s = m_emitters[size_t(c.index)].sample(hit.p, {c.reused, u.y});
        if (!(s.pdf > 0.f) || maxComponent(s.weight) <= 0.f) return {};
        s.pdf *= c.pmf;
        s.weight = s.weight / c.pmf;
        const Vec3f wo = toLocal(frame, s.d);
        const Color f = bsdf.eval(wi, wo);
        if (passesNothing(f, s.weight)) return {};
        const Ray shadow = std::isfinite(s.dist) ? spawnRayTo(hit, s.p)
                                                 : spawnRay(hit, s.d, std::numeric_limits<float>::infinity());
        counts.shadow += 1;
        if (m_embree.occluded(shadow)) return {};
        // A delta light takes the whole weight: no BSDF sample finds it.
        const float weight = s.delta || m_strategy == Strategy::Ems ? 1.f : misWeight(s.pdf, bsdf.pdf(wi, wo));
        return f * s.weight * weight;
    }

    const EmbreeScene &m_embree;
    SceneEmitters m_emitters;
    bool m_hideEmitters;
    uint32_t m_maxDepth, m_rrDepth;
    Strategy m_strategy;
};

Strategy parseStrategy(XmlProps &props) {
    const std::string name = props.getString("strategy", "mis");
    if (name == "mis") return Strategy::Mis;
    if (name == "ems") return Strategy::Ems;
    if (name == "mats") return Strategy::Mats;
    props.failAt("strategy", "strategy must be mis (emitter and BSDF samples), ems (emitter samples) or mats "
                             "(BSDF samples), not \"" + name + "\"");
}

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "path",
    "path tracing with next-event estimation and MIS, Russian roulette (properties: max_depth = -1, "
    "rr_depth = 5, hide_emitters = false, strategy = mis | ems | mats)",
    SceneUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds::all(), /*readsReflectance=*/true,
             /*readsAnyBsdf=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        int maxDepth = -1, rrDepth = 5;
        Strategy strategy = Strategy::Mis;
        if (props) {
            maxDepth = props->getInt("max_depth", -1);
            props->requireRange("max_depth", maxDepth, -1, kMaxDepth);
            rrDepth = props->getInt("rr_depth", 5);
            props->requireRange("rr_depth", rrDepth, 1, kMaxDepth);
            strategy = parseStrategy(*props);
            props->ignore("hide_emitters");  // read by the loader for every integrator type (scene.h)
            props->finish("max_depth, rr_depth, hide_emitters, strategy");
        }
        // -1 as Mitsuba's unsigned max_depth: no vertex count reaches it.
        const uint32_t depth = maxDepth < 0 ? UINT32_MAX : uint32_t(maxDepth);
        return [depth, rrDepth, strategy](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<PathIntegrator>(scene, embree, depth, uint32_t(rrDepth), strategy);
        };
    },
});

}  // namespace mcval
