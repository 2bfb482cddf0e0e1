// The integrators by name. Each integrator's own file registers itself with MCVAL_REGISTER_INTEGRATOR,
// so the loader, the CLI and the Python module learn the list from here and nowhere else.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "../emitters/emitter.h"
#include "integrator.h"

namespace mcval {

class XmlProps;

/// What of a scene an integrator uses. The loader skips (with a note) what the integrator does not
/// use and refuses what it cannot model but would change its answer.
struct SceneUse {
    bool needsPointLight = false;   ///< a scene without a point light is an error
    /// The emitter kinds that light its image: a spot, directional or area emitter of a kind it reads is
    /// read, one of a kind it does not read is skipped with a note; an emitter this renderer does not model
    /// (envmap, projector) is refused where it reads EmitterKind::Unmodelled. Point and constant emitters
    /// are read whatever the integrator.
    EmitterKinds emitters;
    bool readsReflectance = false;  ///< non-diffuse bsdfs would change its answer (refused) or not (skipped)
    /// Whether it reads any BSDF the loader models through eval, pdf and sample; otherwise it reads the
    /// Lambertian albedo alone and refuses the others where it reads the reflectance.
    bool readsAnyBsdf = false;
};

struct IntegratorInfo {
    std::string name;
    std::string description;        ///< one line, for --help
    SceneUse use;
    /// Reads the integrator's own properties from its <integrator> element (nullptr: none given, use
    /// the defaults), checking each, and returns the maker of the integrator so configured.
    std::function<IntegratorMaker(XmlProps *props)> parse;
};

/// Adds an integrator; a second one of the same name is a programming error (aborts).
bool registerIntegrator(IntegratorInfo info);
/// The integrator called `name`, or nullptr.
const IntegratorInfo *findIntegrator(const std::string &name);
/// Every registered name, sorted.
std::vector<std::string> integratorNames();
/// "a, b or c": the names for messages and help.
std::string integratorNameList();

}  // namespace mcval

#define MCVAL_CONCAT_INNER(a, b) a##b
#define MCVAL_CONCAT(a, b) MCVAL_CONCAT_INNER(a, b)
/// Registers an IntegratorInfo at static initialisation. The object file holding it must be linked
/// whole (CMake: the integrators are an OBJECT library), or the linker drops it unreferenced.
#define MCVAL_REGISTER_INTEGRATOR(...) \
    static const bool MCVAL_CONCAT(mcvalIntegratorRegistered, __LINE__) = ::mcval::registerIntegrator(__VA_ARGS__)
