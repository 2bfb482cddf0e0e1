#include "registry.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "../error.h"

namespace mcval {

namespace {

/// Constructed on first use: registrations run during static initialisation, in no fixed order.
std::map<std::string, IntegratorInfo> &registry() {
    static std::map<std::string, IntegratorInfo> integrators;
    return integrators;
}

}  // namespace

bool registerIntegrator(IntegratorInfo info) {
    if (info.name.empty() || !info.parse || registry().count(info.name)) {
        std::fprintf(stderr, "integrator \"%s\" registered twice or incompletely\n", info.name.c_str());
        std::abort();
    }
    const std::string name = info.name;
    registry().emplace(name, std::move(info));
    return true;
}

const IntegratorInfo *findIntegrator(const std::string &name) {
    const auto it = registry().find(name);
    return it == registry().end() ? nullptr : &it->second;
}

std::vector<std::string> integratorNames() {
    std::vector<std::string> names;
    for (const auto &[name, info] : registry()) names.push_back(name);
    return names;  // std::map keeps them sorted
}

std::string integratorNameList() {
    const std::vector<std::string> names = integratorNames();
    std::string list;
    for (size_t i = 0; i < names.size(); ++i)
        list += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    return list;
}

std::unique_ptr<Integrator> createIntegrator(const IntegratorSpec &spec, const SceneDescription &scene,
                                             const EmbreeScene &embree) {
    if (spec.type.empty())
    {
        std::string choices;
        for (const std::string &name : integratorNames()) choices += (choices.empty() ? "" : "|") + name;
        throw SceneError(scene.file, 0, "no integrator: add <integrator type=\"" + choices + "\"/> or pass --integrator");
    }
    const IntegratorInfo *info = findIntegrator(spec.type);
    if (!info)
        throw SceneError(scene.file, 0, "unknown integrator \"" + spec.type + "\": expected " + integratorNameList());
    const IntegratorMaker make = spec.make ? spec.make : info->parse(nullptr);
    return make(scene, embree);
}

}  // namespace mcval
