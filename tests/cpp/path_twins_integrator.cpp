// path's planted wrong twins (test build only): renderer/integrators/path.cpp with one defect each, the
// mistakes a path tracer's author makes most often. tests/cpp/test_path.cpp asserts that the furnace's closed
// form rejects each, where it accepts path itself.
//   path_rr_undivided   Russian roulette that ends paths but does not divide the survivors by their probability
//   path_double_mis     emission found by a BSDF sample counted at full weight beside the MIS-weighted emitter
//                       sample: the light that both strategies find is counted twice
//   path_no_cosine      the cosine at the surface missing: f L in place of f L cos, in both strategies
//   path_depth_plus_one max_depth off by one: one vertex more than Mitsuba's count
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "emitters/scene_emitters.h"
#include "frame.h"
#include "integrators/mis.h"
#include "integrators/registry.h"
#include "xml_props.h"

namespace mcval {

namespace {

enum class Defect { RrUndivided, DoubleMis, NoCosine, DepthPlusOne };

float maxComponent(const Color &c) { return std::max(c.x, std::max(c.y, c.z)); }

class PathTwin final : public Integrator {
public:
    PathTwin(const SceneDescription &scene, const EmbreeScene &embree, Defect defect, uint32_t maxDepth,
             uint32_t rrDepth)
        : m_embree(embree), m_emitters(scene), m_defect(defect),
          m_maxDepth(defect == Defect::DepthPlusOne && maxDepth != UINT32_MAX ? maxDepth + 1 : maxDepth),
          m_rrDepth(rrDepth) {}

    Color Li(const Ray &cameraRay, const Hit *first, Sampler &sampler, RayCounts &counts) const override {
        Color result(0.f, 0.f, 0.f), throughput(1.f, 1.f, 1.f);
        if (m_maxDepth == 0) return result;
        const EmitterSampler &choose = m_emitters.sampler();
        Ray ray = cameraRay;
        Hit hit;
        bool found = first != nullptr;
        if (found) hit = *first;
        Vec3f prevP;
        float prevPdf = 1.f;
        bool prevDelta = true;
        for (uint32_t depth = 0;; ++depth) {
            const int index = found ? hit.emitter : m_emitters.environment();
            if (index >= 0) {
                const EmitterHit at = found ? emitterHit(hit, ray.d) : escaped(ray.d);
                const Emitter &emitter = m_emitters[size_t(index)];
                float weight = 1.f;
                if (!prevDelta && m_defect != Defect::DoubleMis)
                    weight = misWeight(prevPdf, emitter.pdf(prevP, at) * choose.pmf(index));
                result = result + throughput * emitter.eval(at) * weight;
            }
            if (!found || depth + 1 >= m_maxDepth) break;
            const Frame frame(hit.ns);
            const Vec3f wi = toLocal(frame, -ray.d);
            const Bsdf &bsdf = m_embree.bsdf(hit.geom);
            result = result + throughput * emitterSample(hit, frame, wi, bsdf, sampler, counts);

            BsdfSample bs = bsdf.sample(wi, sampler.next2D());
            if (m_defect == Defect::NoCosine && std::fabs(bs.wo.z) > 0.f) bs.weight = bs.weight / std::fabs(bs.wo.z);
            throughput = throughput * bs.weight;
            if (!(maxComponent(throughput) > 0.f)) break;
            prevP = hit.p;
            prevPdf = bs.pdf;
            prevDelta = std::isinf(bs.pdf);
            const Vec3f d = frame.toWorld(bs.wo);
            if (depth + 1 >= m_rrDepth) {
                const float survival = std::min(maxComponent(throughput), 0.95f);
                if (!(sampler.next2D().x < survival)) break;
                if (m_defect != Defect::RrUndivided) throughput = throughput / survival;
            }
            ray = spawnRay(hit, d, 1e30f);
            counts.shadow += 1;
            found = m_embree.intersect(ray, hit);
        }
        return result;
    }

private:
    Color emitterSample(const Hit &hit, const Frame &frame, const Vec3f &wi, const Bsdf &bsdf, Sampler &sampler,
                        RayCounts &counts) const {
        const Vec2f u = sampler.next2D();
        const EmitterSampler::Choice c = m_emitters.sampler().sample(u.x);
        if (c.index < 0) return {};
        EmitterSample s = m_emitters[size_t(c.index)].sample(hit.p, {c.reused, u.y});
        if (!(s.pdf > 0.f) || maxComponent(s.weight) <= 0.f) return {};
        s.pdf *= c.pmf;
        s.weight = s.weight / c.pmf;
        const Ray shadow = std::isfinite(s.dist) ? spawnRayTo(hit, s.p)
                                                 : spawnRay(hit, s.d, std::numeric_limits<float>::infinity());
        counts.shadow += 1;
        if (m_embree.occluded(shadow)) return {};
        const Vec3f wo = toLocal(frame, s.d);
        const float weight = s.delta || m_defect == Defect::DoubleMis ? 1.f : misWeight(s.pdf, bsdf.pdf(wi, wo));
        Color f = bsdf.eval(wi, wo);
        if (m_defect == Defect::NoCosine && std::fabs(wo.z) > 0.f) f = f / std::fabs(wo.z);
        return f * s.weight * weight;
    }

    const EmbreeScene &m_embree;
    SceneEmitters m_emitters;
    Defect m_defect;
    uint32_t m_maxDepth, m_rrDepth;
};

/// path's max_depth and rr_depth, read as path reads them.
std::function<IntegratorMaker(XmlProps *)> parseAs(Defect defect) {
    return [defect](XmlProps *props) -> IntegratorMaker {
        int maxDepth = -1, rrDepth = 5;
        if (props) {
            maxDepth = props->getInt("max_depth", -1);
            props->requireRange("max_depth", maxDepth, -1, 1 << 20);
            rrDepth = props->getInt("rr_depth", 5);
            props->requireRange("rr_depth", rrDepth, 1, 1 << 20);
            props->ignore("hide_emitters");
            props->finish("max_depth, rr_depth, hide_emitters");
        }
        const uint32_t depth = maxDepth < 0 ? UINT32_MAX : uint32_t(maxDepth);
        return [defect, depth, rrDepth](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<PathTwin>(scene, embree, defect, depth, uint32_t(rrDepth));
        };
    };
}

const SceneUse kPathUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds::all(), /*readsReflectance=*/true};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({"path_rr_undivided", "path with Russian roulette that does not divide by survival "
                           "(test build only)", kPathUse, parseAs(Defect::RrUndivided)});
MCVAL_REGISTER_INTEGRATOR({"path_double_mis", "path counting the light a BSDF sample finds at full weight beside "
                           "the MIS-weighted emitter sample (test build only)", kPathUse, parseAs(Defect::DoubleMis)});
MCVAL_REGISTER_INTEGRATOR({"path_no_cosine", "path without the cosine at the surface (test build only)", kPathUse,
                           parseAs(Defect::NoCosine)});
MCVAL_REGISTER_INTEGRATOR({"path_depth_plus_one", "path with max_depth off by one (test build only)", kPathUse,
                           parseAs(Defect::DepthPlusOne)});

}  // namespace mcval
