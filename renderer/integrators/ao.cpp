// ao: ambient occlusion under the constant emitter (radiance 1 without one), cosine-weighted:
// L = rho * L_env * mean(V(w_i)) over `samples` occlusion rays per camera sample.
#include "../frame.h"
#include "../hot.h"
#include "../scene_limits.h"
#include "../warp.h"
#include "../xml_props.h"
#include "registry.h"

namespace mcval {

namespace {

/// ao's estimate for a packet (a free function: it is compiled per ISA, which a virtual one cannot be).
/// The j-th occlusion ray of every lane goes to Embree as one packet (their directions differ: an
/// incoherent packet).
MCVAL_HOT void aoPacket(const EmbreeScene &embree, const Color &environment, int samples, const SamplePacket &packet,
                    const Sampler &sampler, Color *out, RayCounts &counts) {
    const int n = packet.count;
    bool front[kPacketSize];
    Frame frames[kPacketSize];
    int visible[kPacketSize];
    int traced = 0;
    for (int i = 0; i < n; ++i) {
        // A camera ray that escapes returns 0 (the environment itself is hidden); so does a back face.
        front[i] = packet.lanes.front(i);
        if (front[i]) frames[i] = Frame({packet.lanes.nx[i], packet.lanes.ny[i], packet.lanes.nz[i]});
        visible[i] = 0;
        traced += front[i];
    }
    if (traced > 0) {
        OcclusionPacket rays;
        for (int j = 0; j < samples; ++j) {
            rays.clear();
            for (int i = 0; i < n; ++i) {
                if (!front[i]) continue;
                // Cosine-weighted sampling cancels the cosine over its pdf: each unoccluded ray
                // counts rho * L_env.
                const Vec2f u = sampler.sample2D(packet.first + static_cast<uint32_t>(i), 1 + static_cast<uint32_t>(j));
                const Vec3f wi = frames[i].toWorld(squareToCosineHemisphere(u));
                rays.set(i, packet.lanes.spawnOrigin(i, wi), wi, 1e30f);
            }
            embree.occluded(rays, /*coherent=*/false);
            for (int i = 0; i < n; ++i) visible[i] += front[i] && !rays.blocked(i);
        }
        counts.shadow += static_cast<uint64_t>(traced) * static_cast<uint64_t>(samples);
    }
    for (int i = 0; i < n; ++i) {
        out[i] = front[i] ? embree.reflectance(packet.lanes.geom[i]) * environment *
                                (static_cast<float>(visible[i]) / static_cast<float>(samples))
                          : Color(0.f, 0.f, 0.f);
    }
}

class AoIntegrator final : public Integrator {
public:
    AoIntegrator(const SceneDescription &scene, const EmbreeScene &embree, int samples)
        : m_embree(embree), m_environment(scene.environment.value_or(Color(1.f, 1.f, 1.f))), m_samples(samples) {}

    void LiPacket(const SamplePacket &packet, Sampler &sampler, Color *out, RayCounts &counts) const override {
        aoPacket(m_embree, m_environment, m_samples, packet, sampler, out, counts);
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
