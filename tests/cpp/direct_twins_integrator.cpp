// direct's planted wrong twins (test build only): renderer/integrators/direct.cpp with one defect each, the
// mistakes its authors make most often. tests/images/test_direct_twins.py asserts that the image suite fails
// each against Mitsuba and the closed form, and that the strategy check names the strategy a defect biases.
//   direct_area_pdf    the area light's density left in area measure (no distance^2 / cos): an emitter
//                      sample carries L / p_A where L / p_omega is right, and MIS weighs it by p_A
//   direct_double_mis  MIS weights that double count: each strategy keeps its whole weight where both are
//                      drawn, so their sum counts the light twice (either strategy alone is right)
//   direct_no_cosine   the cosine at the surface missing: f L in place of f L cos, in both strategies alike
#include <cmath>
#include <limits>

#include "emitters/scene_emitters.h"
#include "frame.h"
#include "integrators/registry.h"
#include "xml_props.h"

namespace mcval {

namespace {

enum class Defect { AreaPdf, DoubleMis, NoCosine };

float misWeight(float pdfA, float pdfB) {
    pdfA *= pdfA;
    pdfB *= pdfB;
    const float w = pdfA / (pdfA + pdfB);
    return std::isfinite(w) ? w : 0.f;
}

Vec3f toLocal(const Frame &frame, const Vec3f &v) { return {dot(v, frame.s), dot(v, frame.t), dot(v, frame.n)}; }

/// A solid-angle density at a point `dist` away, seen at cosine `cosine` there, in area measure.
float inArea(float pdf, float cosine, float dist) { return pdf * std::fabs(cosine) / (dist * dist); }

class DirectTwin final : public Integrator {
public:
    DirectTwin(const SceneDescription &scene, const EmbreeScene &embree, Defect defect, int emitterSamples,
               int bsdfSamples)
        : m_embree(embree), m_emitters(scene), m_defect(defect), m_hideEmitters(scene.hideEmitters.value_or(false)),
          m_emitterSamples(emitterSamples), m_bsdfSamples(bsdfSamples),
          m_fracBsdf(float(bsdfSamples) / float(emitterSamples + bsdfSamples)),
          m_fracLum(float(emitterSamples) / float(emitterSamples + bsdfSamples)) {}

    Color Li(const Ray &ray, const Hit *first, Sampler &sampler, RayCounts &counts) const override {
        Color result(0.f, 0.f, 0.f);
        if (!first) return result;  // the lit-plane scenes: every camera ray meets the floor, never the light
        const Hit &hit = *first;
        if (!m_hideEmitters && hit.emitter >= 0) result = m_emitters[size_t(hit.emitter)].eval(emitterHit(hit, ray.d));
        const Frame frame(hit.ns);
        const Vec3f wi = toLocal(frame, -ray.d);
        const Bsdf &bsdf = m_embree.bsdf(hit.geom);
        const EmitterSampler &choose = m_emitters.sampler();
        const bool both = m_emitterSamples > 0 && m_bsdfSamples > 0;

        for (int i = 0; i < m_emitterSamples; ++i) {
            const Vec2f u = sampler.next2D();
            const EmitterSampler::Choice c = choose.sample(u.x);
            if (c.index < 0) continue;
            EmitterSample s = m_emitters[size_t(c.index)].sample(hit.p, {c.reused, u.y});
            if (!(s.pdf > 0.f)) continue;
            if (m_defect == Defect::AreaPdf && !s.delta && std::isfinite(s.dist)) {
                const float area = inArea(s.pdf, dot(s.n, -s.d), s.dist);
                s.weight = s.weight * (s.pdf / area);  // L / p_A: the distance^2 / cos never applied
                s.pdf = area;
            }
            s.pdf *= c.pmf;
            s.weight = s.weight / c.pmf;
            const Ray shadow = std::isfinite(s.dist) ? spawnRayTo(hit, s.p)
                                                     : spawnRay(hit, s.d, std::numeric_limits<float>::infinity());
            counts.shadow += 1;
            if (m_embree.occluded(shadow)) continue;
            const Vec3f wo = toLocal(frame, s.d);
            Color f = bsdf.eval(wi, wo);
            if (m_defect == Defect::NoCosine) f = wo.z > 0.f ? f / wo.z : Color(0.f, 0.f, 0.f);
            float mis = s.delta ? 1.f : misWeight(s.pdf * m_fracLum, bsdf.pdf(wi, wo) * m_fracBsdf);
            if (m_defect == Defect::DoubleMis && both) mis = 1.f;
            result = result + f * s.weight * (mis / float(m_emitterSamples));
        }

        for (int i = 0; i < m_bsdfSamples; ++i) {
            const BsdfSample bs = bsdf.sample(wi, sampler.next2D());
            if (bs.weight.x == 0.f && bs.weight.y == 0.f && bs.weight.z == 0.f) continue;
            const Vec3f d = frame.toWorld(bs.wo);
            Hit next;
            counts.shadow += 1;
            const bool hitSomething = m_embree.intersect(spawnRay(hit, d, 1e30f), next);
            const int index = hitSomething ? next.emitter : m_emitters.environment();
            if (index < 0) continue;
            const EmitterHit at = hitSomething ? emitterHit(next, d) : escaped(d);
            float emitterPdf = m_emitters[size_t(index)].pdf(hit.p, at) * choose.pmf(index);
            if (m_defect == Defect::AreaPdf && hitSomething) emitterPdf = inArea(emitterPdf, dot(at.ng, -d), at.dist);
            Color weight = bs.weight;
            if (m_defect == Defect::NoCosine) weight = bs.wo.z > 0.f ? weight / bs.wo.z : Color(0.f, 0.f, 0.f);
            float mis = misWeight(bs.pdf * m_fracBsdf, emitterPdf * m_fracLum);
            if (m_defect == Defect::DoubleMis && both) mis = 1.f;
            result = result + weight * m_emitters[size_t(index)].eval(at) * (mis / float(m_bsdfSamples));
        }
        return result;
    }

private:
    const EmbreeScene &m_embree;
    SceneEmitters m_emitters;
    Defect m_defect;
    bool m_hideEmitters;
    int m_emitterSamples, m_bsdfSamples;
    float m_fracBsdf, m_fracLum;
};

/// direct's properties, read as direct reads them.
std::function<IntegratorMaker(XmlProps *)> parseAs(Defect defect) {
    return [defect](XmlProps *props) -> IntegratorMaker {
        int emitterSamples = 1, bsdfSamples = 1;
        if (props) {
            const int shading = props->getInt("shading_samples", 1);
            props->requireRange("shading_samples", shading, 0, 1024);
            emitterSamples = props->getInt("emitter_samples", shading);
            props->requireRange("emitter_samples", emitterSamples, 0, 1024);
            bsdfSamples = props->getInt("bsdf_samples", shading);
            props->requireRange("bsdf_samples", bsdfSamples, 0, 1024);
            props->ignore("hide_emitters");
            props->finish("emitter_samples, bsdf_samples, shading_samples, hide_emitters");
            if (emitterSamples + bsdfSamples == 0)
                props->failAt("emitter_samples", "direct needs at least one emitter or BSDF sample");
        }
        return [defect, emitterSamples, bsdfSamples](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<DirectTwin>(scene, embree, defect, emitterSamples, bsdfSamples);
        };
    };
}

const SceneUse kDirectUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds::all(), /*readsReflectance=*/true};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({"direct_area_pdf", "direct with the area light's density left in area measure (test build only)",
                           kDirectUse, parseAs(Defect::AreaPdf)});
MCVAL_REGISTER_INTEGRATOR({"direct_double_mis", "direct with MIS weights that double count (test build only)",
                           kDirectUse, parseAs(Defect::DoubleMis)});
MCVAL_REGISTER_INTEGRATOR({"direct_no_cosine", "direct without the cosine at the surface (test build only)",
                           kDirectUse, parseAs(Defect::NoCosine)});

}  // namespace mcval
