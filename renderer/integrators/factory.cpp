#include "../error.h"
#include "ao.h"
#include "normals.h"
#include "simple.h"

namespace mcval {

std::unique_ptr<Integrator> createIntegrator(const IntegratorSpec &spec, const SceneDescription &scene,
                                             const EmbreeScene &embree) {
    if (spec.type == "normals") return std::make_unique<NormalsIntegrator>();
    if (spec.type == "simple") return std::make_unique<SimpleIntegrator>(scene, embree);
    if (spec.type == "ao") return std::make_unique<AoIntegrator>(scene, embree, spec.aoSamples);
    if (spec.type.empty())
        throw SceneError(scene.file, 0, "no integrator: add <integrator type=\"normals|simple|ao\"/> or pass --integrator");
    throw SceneError(scene.file, 0, "unknown integrator \"" + spec.type + "\": expected normals, simple or ao");
}

}  // namespace mcval
