// albedo (test build only): the diffuse reflectance at the first hit, 0 where the ray escapes. It
// exists to show that one file is all an integrator needs: the registry, the CLI's help, the Python
// module and the harness pick it up with no other edit.
#include "integrators/registry.h"
#include "xml_props.h"

namespace mcval {

namespace {

class AlbedoIntegrator final : public Integrator {
public:
    explicit AlbedoIntegrator(const EmbreeScene &embree) : m_embree(embree) {}
    Color Li(const Ray &, const Hit *hit, Sampler &, RayCounts &) const override {
        return hit ? m_embree.reflectance(hit->geom) : Color(0.f, 0.f, 0.f);
    }

private:
    const EmbreeScene &m_embree;
};

}  // namespace

MCVAL_REGISTER_INTEGRATOR({
    "albedo",
    "diffuse reflectance at the first hit (test build only)",
    SceneUse{/*needsPointLight=*/false, /*emitters=*/EmitterKinds{}, /*readsReflectance=*/true},
    [](XmlProps *props) -> IntegratorMaker {
        if (props) props->finish("no properties");
        return [](const SceneDescription &, const EmbreeScene &embree) { return std::make_unique<AlbedoIntegrator>(embree); };
    },
});

}  // namespace mcval
