#include "scene_emitters.h"

#include "area.h"
#include "constant.h"
#include "delta_lights.h"
#include "envmap.h"

namespace mcval {

namespace {

template <typename Shape>
void addAreaEmitters(const std::vector<Shape> &shapes, std::vector<std::unique_ptr<Emitter>> &out) {
    for (const Shape &shape : shapes)
        if (shape.areaRadiance) out.push_back(std::make_unique<AreaEmitter>(*shape.areaRadiance, makeShapeSampler(shape)));
}

/// How many emitters list the area emitters before them (SceneEmitters' order).
size_t countEmitters(const SceneDescription &scene) {
    size_t n = scene.pointLights.size() + scene.spotLights.size() + scene.directionalLights.size() +
               (scene.environment ? 1 : 0) + (scene.envmap ? 1 : 0);
    const auto count = [&n](const auto &shapes) {
        for (const auto &shape : shapes) n += shape.areaRadiance ? 1 : 0;
    };
    count(scene.meshes);
    count(scene.spheres);
    count(scene.disks);
    count(scene.cylinders);
    return n;
}

}  // namespace

SceneEmitters::SceneEmitters(const SceneDescription &scene) : m_sampler(countEmitters(scene)) {
    // Embree's geometry order: meshes, spheres, disks, cylinders (embree_scene.h).
    addAreaEmitters(scene.meshes, m_emitters);
    addAreaEmitters(scene.spheres, m_emitters);
    addAreaEmitters(scene.disks, m_emitters);
    addAreaEmitters(scene.cylinders, m_emitters);
    for (const PointLight &light : scene.pointLights) m_emitters.push_back(std::make_unique<PointEmitter>(light));
    for (const SpotLight &light : scene.spotLights) m_emitters.push_back(std::make_unique<SpotEmitter>(light));
    for (const DirectionalLight &light : scene.directionalLights)
        m_emitters.push_back(std::make_unique<DirectionalEmitter>(light));
    if (scene.environment) {
        m_environment = int(m_emitters.size());
        m_emitters.push_back(std::make_unique<ConstantEmitter>(*scene.environment));
    } else if (scene.envmap) {
        m_environment = int(m_emitters.size());
        m_emitters.push_back(std::make_unique<EnvmapEmitter>(*scene.envmap));
    }
}

}  // namespace mcval
