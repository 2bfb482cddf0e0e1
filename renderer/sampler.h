// Random numbers: PCG32 streams, one per pixel and batch, so results do not depend on threads.
#pragma once

#include <cstdint>

#include "vector.h"

namespace mcr {

/// PCG32 (O'Neill 2014): 64-bit state, selectable stream.
class Pcg32 {
public:
    Pcg32(uint64_t seed, uint64_t stream) {
        m_inc = (stream << 1u) | 1u;
        m_state = 0;
        nextUInt();
        m_state += seed;
        nextUInt();
    }

    uint32_t nextUInt() {
        const uint64_t old = m_state;
        m_state = old * 6364136223846793005ULL + m_inc;
        const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
    }

    /// Uniform in [0, 1): 24 random mantissa bits.
    float nextFloat() { return static_cast<float>(nextUInt() >> 8) * 0x1p-24f; }

private:
    uint64_t m_state, m_inc;
};

/// Independent uniform samples for one pixel of one batch.
class Sampler {
public:
    Sampler(uint64_t seed, uint64_t batch, uint64_t pixel) : m_rng(mix(seed, batch), pixel) {}
    float next1D() { return m_rng.nextFloat(); }
    Vec2f next2D() {
        const float a = m_rng.nextFloat();
        return {a, m_rng.nextFloat()};
    }

private:
    /// SplitMix64 finaliser: distinct (seed, batch) pairs give unrelated states.
    static uint64_t mix(uint64_t seed, uint64_t batch) {
        uint64_t z = seed * 0x9E3779B97F4A7C15ULL + batch + 0x632BE59BD9B4E019ULL;
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
        return z ^ (z >> 31);
    }
    Pcg32 m_rng;
};

}  // namespace mcr
