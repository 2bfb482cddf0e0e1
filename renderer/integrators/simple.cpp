// simple: direct light from point emitters on diffuse surfaces, with shadow rays (Nori's simple
// integrator): L = (rho / pi) * I * max(0, cos) / r^2 * V, summed over the point lights.
#include <cmath>

#include "../warp.h"
#include "../xml_props.h"
#include "registry.h"

namespace mcval {

namespace {

class SimpleIntegrator final : public Integrator {
public:
    SimpleIntegrator(const SceneDescription &scene, const EmbreeScene &embree) : m_scene(scene), m_embree(embree) {}

    /// Per light, the shadow rays of the whole packet go to Embree as one coherent packet: they start
    /// near one another (one pixel) and end at the same point.
    void LiPacket(const SamplePacket &packet, Sampler &, Color *out, RayCounts &counts) const override {
        const int n = packet.count;
        bool front[kPacketSize];
        for (int i = 0; i < n; ++i) {
            // One-sided diffuse, as Mitsuba's: black seen from behind the shading normal.
            front[i] = packet.found[i] && dot(packet.hits[i].ns, packet.rays[i].d) < 0.f;
            out[i] = {0.f, 0.f, 0.f};
        }
        for (const PointLight &light : m_scene.pointLights) {
            Ray shadow[kPacketSize];
            bool active[kPacketSize], blocked[kPacketSize];
            float weight[kPacketSize];
            int traced = 0;
            for (int i = 0; i < n; ++i) {
                active[i] = false;
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
                shadow[i] = spawnRay(hit, wi, dist * (1.f - 1e-4f));
                weight[i] = cosTheta / dist2;
                active[i] = true;
                ++traced;
            }
            if (traced == 0) continue;
            counts.shadow += static_cast<uint64_t>(traced);
            m_embree.occluded16(shadow, active, n, blocked, /*coherent=*/true);
            for (int i = 0; i < n; ++i)
                if (active[i] && !blocked[i]) out[i] = out[i] + light.intensity * weight[i];
        }
        for (int i = 0; i < n; ++i)
            if (front[i]) out[i] = m_embree.reflectance(packet.hits[i].geom) * out[i] * kInvPi;
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
