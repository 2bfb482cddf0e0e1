// simple: direct light from point emitters on diffuse surfaces, with shadow rays (Nori's simple
// integrator): L = (rho / pi) * I * max(0, cos) / r^2 * V, summed over the point lights.
#include <cmath>

#include "../hot.h"
#include "../warp.h"
#include "../xml_props.h"
#include "registry.h"

namespace mcval {

namespace {

/// simple's estimate for a packet (a free function: it is compiled per ISA, which a virtual one cannot
/// be). Per light, the shadow rays of the whole packet go to Embree as one coherent packet: they start
/// near one another (one pixel) and end at the same point. The arithmetic is the scalar formula's,
/// lane by lane (L = rho / pi * sum I cos / r^2 over unshadowed lights), in the same order.
MCVAL_HOT void simplePacket(const std::vector<PointLight> &lights, const EmbreeScene &embree, const SamplePacket &packet,
                            Color *out, RayCounts &counts) {
    const HitPacket &h = packet.lanes;
    alignas(64) int front[kPacketSize], back[kPacketSize];
    // The shading normal on the side the ray came from (a two-sided surface's back is lit too).
    alignas(64) float nx[kPacketSize], ny[kPacketSize], nz[kPacketSize];
    for (int i = 0; i < kPacketSize; ++i) {
        back[i] = (h.found[i] != 0) & !h.front(i);
        front[i] = (i < packet.count) & (h.found[i] != 0) & (!back[i] | embree.twoSided(h.geom[i]));
        const float side = back[i] ? -1.f : 1.f;
        nx[i] = side * h.nx[i]; ny[i] = side * h.ny[i]; nz[i] = side * h.nz[i];
    }
    alignas(64) float sumR[kPacketSize] = {}, sumG[kPacketSize] = {}, sumB[kPacketSize] = {};
    alignas(64) float weight[kPacketSize];
    OcclusionPacket shadow;
    RTCRay16 &r = shadow.rays;
    for (const PointLight &light : lights) {
        int traced = 0;
        for (int i = 0; i < kPacketSize; ++i) {
            const float tx = light.position.x - h.px[i], ty = light.position.y - h.py[i],
                        tz = light.position.z - h.pz[i];
            const float dist2 = tx * tx + ty * ty + tz * tz;
            const float dist = std::sqrt(dist2);
            const float wx = tx / dist, wy = ty / dist, wz = tz / dist;
            const float cosTheta = nx[i] * wx + ny[i] * wy + nz[i] * wz;
            const bool on = (front[i] != 0) & (dist2 > 0.f) & (cosTheta > 0.f);
            const Vec3f o = h.spawnOrigin(i, {wx, wy, wz});
            r.org_x[i] = o.x; r.org_y[i] = o.y; r.org_z[i] = o.z;
            r.dir_x[i] = wx; r.dir_y[i] = wy; r.dir_z[i] = wz;
            r.tnear[i] = 0.f;
            // Stop just short of the light: nothing behind it may shadow.
            r.tfar[i] = dist * (1.f - 1e-4f);
            shadow.valid[i] = on ? -1 : 0;
            weight[i] = on ? cosTheta / dist2 : 0.f;
            traced += on;
        }
        if (traced == 0) continue;
        shadow.active = traced;
        counts.shadow += static_cast<uint64_t>(traced);
        embree.occluded(shadow, /*coherent=*/true);
        // Branch-free, so it runs in SIMD: an unlit lane adds I * 0 = +0, which leaves its sum's bits alone.
        const float ir = light.intensity.x, ig = light.intensity.y, ib = light.intensity.z;
        for (int i = 0; i < kPacketSize; ++i) {
            const bool lit = (shadow.valid[i] != 0) & !(r.tfar[i] < 0.f);  // Embree sets tfar to -inf on a hit
            const float w = lit ? weight[i] : 0.f;
            sumR[i] += ir * w;
            sumG[i] += ig * w;
            sumB[i] += ib * w;
        }
    }
    for (int i = 0; i < packet.count; ++i)
        out[i] = front[i] ? (back[i] ? embree.backReflectance(h.geom[i]) : embree.reflectance(h.geom[i])) *
                                Color(sumR[i], sumG[i], sumB[i]) * kInvPi
                            : Color(0.f, 0.f, 0.f);
}

class SimpleIntegrator final : public Integrator {
public:
    SimpleIntegrator(const SceneDescription &scene, const EmbreeScene &embree) : m_scene(scene), m_embree(embree) {}

    void LiPacket(const SamplePacket &packet, Sampler &, Color *out, RayCounts &counts) const override {
        simplePacket(m_scene.pointLights, m_embree, packet, out, counts);
    }

private:
    const SceneDescription &m_scene;
    const EmbreeScene &m_embree;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "simple",
    "point lights on diffuse surfaces, with shadow rays",
    SceneUse{/*needsPointLight=*/true, /*emitters=*/EmitterKinds{EmitterKind::Point}, /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        if (props) props->finish("no properties");
        return [](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<SimpleIntegrator>(scene, embree);
        };
    },
});

}  // namespace mcval
