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
/// near one another (one pixel) and end at the same point.
MCVAL_HOT void simplePacket(const std::vector<PointLight> &lights, const EmbreeScene &embree, const SamplePacket &packet,
                            Color *out, RayCounts &counts) {
    const int n = packet.count;
    bool front[kPacketSize];
    for (int i = 0; i < n; ++i) {
        // One-sided diffuse, as Mitsuba's: black seen from behind the shading normal.
        front[i] = packet.found[i] && dot(packet.hits[i].ns, packet.rays[i].d) < 0.f;
        out[i] = {0.f, 0.f, 0.f};
    }
    OcclusionPacket shadow;
    for (const PointLight &light : lights) {
        float weight[kPacketSize];
        shadow.clear();
        for (int i = 0; i < n; ++i) {
            if (!front[i]) continue;
            const Hit &hit = packet.hits[i];
            const Vec3f toLight = light.position - hit.p;
            const float dist2 = squaredNorm(toLight);
            if (!(dist2 > 0.f)) continue;
            const float dist = std::sqrt(dist2);
            const Vec3f wi = toLight / dist;
            const float cosTheta = dot(hit.ns, wi);
            if (cosTheta <= 0.f) continue;
            // Stop just short of the light: nothing behind it may shadow.
            shadow.set(i, spawnOrigin(hit, wi), wi, dist * (1.f - 1e-4f));
            weight[i] = cosTheta / dist2;
        }
        if (shadow.active == 0) continue;
        counts.shadow += static_cast<uint64_t>(shadow.active);
        embree.occluded(shadow, /*coherent=*/true);
        for (int i = 0; i < n; ++i)
            if (shadow.valid[i] && !shadow.blocked(i)) out[i] = out[i] + light.intensity * weight[i];
    }
    for (int i = 0; i < n; ++i)
        if (front[i]) out[i] = embree.reflectance(packet.hits[i].geom) * out[i] * kInvPi;
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
    SceneUse{/*needsPointLight=*/true, /*areaEmittersLight=*/true, /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        if (props) props->finish("no properties");
        return [](const SceneDescription &scene, const EmbreeScene &embree) {
            return std::make_unique<SimpleIntegrator>(scene, embree);
        };
    },
});

}  // namespace mcval
