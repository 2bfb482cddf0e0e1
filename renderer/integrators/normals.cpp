// normals: the shading normal at the first hit, as Mitsuba's aov "nn:sh_normal". Deterministic
// per ray, so it checks camera and geometry before any noise enters.
#include "../xml_props.h"
#include "registry.h"

namespace mcval {

namespace {

class NormalsIntegrator final : public Integrator {
public:
    Color Li(const Ray &, const Hit *hit, Sampler &, RayCounts &) const override {
        return hit ? hit->ns : Color(0.f, 0.f, 0.f);
    }
    /// Li for a packet, read straight from its SoA hits (a lane without a hit holds a zero normal).
    void LiPacket(const SamplePacket &packet, Sampler &, Color *out, RayCounts &) const override {
        const HitPacket &h = packet.lanes;
        for (int i = 0; i < packet.count; ++i) out[i] = Color(h.nx[i], h.ny[i], h.nz[i]);
    }
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "normals",
    "shading normal at the first hit (0 where the ray escapes)",
    SceneUse{},  // no light, no reflectance: emitters and bsdfs are skipped
    [](XmlProps *props) -> IntegratorMaker {
        if (props) props->finish("no properties");
        return [](const SceneDescription &, const EmbreeScene &) { return std::make_unique<NormalsIntegrator>(); };
    },
});

}  // namespace mcval
