// Which emitter a light sample goes to: Mitsuba's default, uniform over the scene's emitters.
#pragma once

#include <algorithm>
#include <cstddef>

#include "../warp.h"

namespace mcval {

/// The distribution over emitters that an integrator draws a light from and asks the probability of.
class EmitterSampler {
public:
    explicit EmitterSampler(size_t count) : m_count(count) {}
    struct Choice {
        int index = -1;   ///< -1 when the scene has no emitter
        float pmf = 0.f;
        float reused = 0.f;  ///< u rescaled to [0, 1) within the choice, for the emitter's own sample
    };
    /// The emitter that u in [0, 1) selects, its probability, and u reused (Mitsuba's sample_reuse).
    Choice sample(float u) const {
        if (m_count == 0) return {};
        const float scaled = u * float(m_count);
        const int index = std::min(int(scaled), int(m_count) - 1);
        return {index, pmf(index), std::min(scaled - float(index), kOneMinusEpsilon)};
    }
    /// The probability of emitter `index`.
    float pmf(int index) const {
        return index >= 0 && size_t(index) < m_count ? 1.f / float(m_count) : 0.f;
    }
    size_t size() const { return m_count; }

private:
    size_t m_count;
};

}  // namespace mcval
