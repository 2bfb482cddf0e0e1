// What loading a scene file says: the tests that check a refusal's file, line and words.
#pragma once

#include <string>

#include "error.h"
#include "render.h"

namespace mcval::test {

/// The SceneError message of loading `path` under `integrator`, or "" if it loads.
inline std::string loadError(const std::string &path, const std::string &integrator) {
    try {
        loadScene(path, {}, integrator);
    } catch (const SceneError &e) {
        return e.what();
    }
    return "";
}

}  // namespace mcval::test
