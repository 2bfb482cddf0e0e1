// The two tiers of errors: bad input (SceneError, shown to the user) and broken invariants (MCR_ASSERT).
#pragma once

#include <cassert>
#include <stdexcept>
#include <string>

namespace mcval {

/// A user error in a scene file or on the command line; the message names file, line and what was expected.
class SceneError : public std::runtime_error {
public:
    explicit SceneError(const std::string &message) : std::runtime_error(message) {}
    SceneError(const std::string &file, int line, const std::string &message)
        : std::runtime_error(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message) {}
};

}  // namespace mcval

/// Internal invariant; compiled out in release builds.
#define MCR_ASSERT(cond) assert(cond)
