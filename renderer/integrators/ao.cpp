// ao: ambient occlusion under the constant emitter (radiance 1 without one), cosine-weighted:
// L = L_env * mean(V(w_i)) over `samples` occlusion rays per camera sample. It reads no material: every
// surface is an opaque white diffuse one, lit on its back only where its bsdf is twosided. A camera ray that
// escapes sees black, or L_env where the file's integrator says hide_emitters = false (Mitsuba's and
// Nori's convention; black is the suite's, so that the image is the occlusion alone).
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
/// incoherent packet). Each loop runs over all kPacketSize lanes without branches, so that it compiles to
/// SIMD; a lane without a front-facing hit traces nothing and returns 0.
MCVAL_HOT void aoPacket(const EmbreeScene &embree, const Color &environment, const Color &background, int samples,
                        const SamplePacket &packet, const Sampler &sampler, Color *out, RayCounts &counts) {
    const HitPacket &h = packet.lanes;
    alignas(64) int front[kPacketSize], visible[kPacketSize], back[kPacketSize];
    // The shading normal on the side the ray came from (a two-sided surface's back is lit too).
    alignas(64) float nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];
    // The tangent frame around each lane's shading normal, in SoA form (an array of Frames would keep
    // the loops below from SIMD: 30 % slower).
    alignas(64) float sx[kPacketSize], sy[kPacketSize], sz[kPacketSize], tx[kPacketSize], ty[kPacketSize],
        tz[kPacketSize];
    int traced = 0;
    for (int i = 0; i < kPacketSize; ++i) {
        // A one-sided back face returns 0; a camera ray that escapes returns the background.
        back[i] = (h.found[i] != 0) & !h.front(i);
        front[i] = (i < packet.count) & (h.found[i] != 0) & (!back[i] | embree.twoSided(h.geom[i]));
        visible[i] = 0;
        traced += front[i];
        const float side = back[i] ? -1.f : 1.f;
        nx[i] = side * h.nx[i]; ny[i] = side * h.ny[i]; nz[i] = side * h.nz[i];
        const Frame frame({nx[i], ny[i], nz[i]});
        sx[i] = frame.s.x; sy[i] = frame.s.y; sz[i] = frame.s.z;
        tx[i] = frame.t.x; ty[i] = frame.t.y; tz[i] = frame.t.z;
    }
    if (traced > 0) {
        OcclusionPacket rays;
        RTCRay16 &r = rays.rays;
        alignas(64) float ux[kPacketSize], uy[kPacketSize];
        for (int j = 0; j < samples; ++j) {
            const auto pair = 1 + static_cast<uint32_t>(j);
            if (sampler.type() == SamplerType::Independent) {
                for (int i = 0; i < kPacketSize; ++i) {
                    const Vec2f u = sampler.independent2D(packet.first + static_cast<uint32_t>(i), pair);
                    ux[i] = u.x;
                    uy[i] = u.y;
                }
            } else {
                for (int i = 0; i < kPacketSize; ++i) {
                    const Vec2f u = sampler.sample2D(packet.first + static_cast<uint32_t>(i), pair);
                    ux[i] = u.x;
                    uy[i] = u.y;
                }
            }
            for (int i = 0; i < kPacketSize; ++i) {
                // Cosine-weighted sampling cancels the cosine over its pdf: each unoccluded ray
                // counts L_env.
                const Vec3f l = squareToCosineHemisphere({ux[i], uy[i]});
                // Frame::toWorld: s l.x + t l.y + n l.z.
                const Vec3f wi{sx[i] * l.x + tx[i] * l.y + nx[i] * l.z, sy[i] * l.x + ty[i] * l.y + ny[i] * l.z,
                               sz[i] * l.x + tz[i] * l.y + nz[i] * l.z};
                const Vec3f o = h.spawnOrigin(i, wi);
                r.org_x[i] = o.x; r.org_y[i] = o.y; r.org_z[i] = o.z;
                r.dir_x[i] = wi.x; r.dir_y[i] = wi.y; r.dir_z[i] = wi.z;
                r.tnear[i] = 0.f;
                r.tfar[i] = 1e30f;
                rays.valid[i] = front[i] ? -1 : 0;
            }
            rays.active = traced;
            embree.occluded(rays, /*coherent=*/false);
            for (int i = 0; i < kPacketSize; ++i) visible[i] += front[i] & !(r.tfar[i] < 0.f);  // -inf: blocked
        }
        counts.shadow += static_cast<uint64_t>(traced) * static_cast<uint64_t>(samples);
    }
    for (int i = 0; i < packet.count; ++i) {
        out[i] = front[i] ? environment *
                                (static_cast<float>(visible[i]) / static_cast<float>(samples))
                 : h.found[i] ? Color(0.f, 0.f, 0.f)
                              : background;
    }
}

class AoIntegrator final : public Integrator {
public:
    AoIntegrator(const SceneDescription &scene, const EmbreeScene &embree, int samples)
        : m_embree(embree), m_environment(scene.environment.value_or(Color(1.f, 1.f, 1.f))),
          m_background(scene.hideEmitters.value_or(true) ? Color(0.f, 0.f, 0.f) : m_environment), m_samples(samples) {}

    void LiPacket(const SamplePacket &packet, Sampler &sampler, Color *out, RayCounts &counts) const override {
        aoPacket(m_embree, m_environment, m_background, m_samples, packet, sampler, out, counts);
    }

private:
    const EmbreeScene &m_embree;
    Color m_environment, m_background;
    int m_samples;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "ao",
    "ambient occlusion under the constant emitter, cosine-weighted (properties: samples, hide_emitters = true)",
    SceneUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds{EmitterKind::Constant}, /*readsReflectance=*/false},
    [](XmlProps *props) -> IntegratorMaker {
        int samples = 1;
        if (props) {
            samples = props->getInt("samples", 1);
            props->requireRange("samples", samples, 1, kMaxAoSamples);
            props->ignore("hide_emitters");  // read by the loader for every integrator type (scene.h)
            props->finish("samples");
        }
        return [samples](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<AoIntegrator>(scene, embree, samples);
        };
    },
});

}  // namespace mcval
