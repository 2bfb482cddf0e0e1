// Sample values, as the scene's <sampler type="..."> asks:
//
// independent  independent uniform values, as Mitsuba's sampler of that name: each (pixel, batch,
//              sample, dimension) is hashed to its own value, so nothing is stratified and the
//              error of a batch falls as 1/sqrt(spp).
// sobol        Owen-scrambled Sobol points (pbrt-v4's PaddedSobolSampler with Owen scrambling):
//              each sample of a pixel draws 2D points from a (0,2)-sequence (the first two Sobol
//              dimensions), one independently scrambled sequence per 2D dimension pair (pixel
//              jitter, then each AO direction). Burley, "Practical Hash-based Owen Scrambling",
//              JCGT 2020. Stratified within a batch; each batch's scrambles are its own, so batches
//              stay independent unbiased estimates. Mitsuba has no sampler of this name: its closest
//              is `ldsampler`, scrambled (0,2)-sequences as well.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "vector.h"

namespace mcval {

namespace detail {

inline uint32_t reverseBits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
    return __builtin_bswap32(x);  // the byte swap does the last two steps at once
}

/// Laine and Karras' hash, a permutation that only lets bits affect higher bits.
inline uint32_t laineKarras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// Owen scrambling of the bits of x (most significant first), keyed by seed.
inline uint32_t owenScramble(uint32_t x, uint32_t seed) { return reverseBits(laineKarras(reverseBits(x), seed)); }

/// The second Sobol dimension (the first is the bit reversal of the index), bit by bit: the XOR of
/// the direction numbers of the index's set bits.
inline uint32_t sobolSecondBitwise(uint32_t index) {
    uint32_t result = 0;
    for (uint32_t v = 1u << 31; index != 0; index >>= 1, v ^= v >> 1)
        if (index & 1u) result ^= v;
    return result;
}

/// sobolSecondBitwise for every value of each byte of the index: the map is linear over GF(2), so the
/// index's four bytes look up four tables and XOR them (4 loads instead of up to 32 steps).
struct SobolSecondTables {
    uint32_t byte[4][256];
    SobolSecondTables() {
        for (uint32_t b = 0; b < 4; ++b)
            for (uint32_t v = 0; v < 256; ++v) byte[b][v] = sobolSecondBitwise(v << (8 * b));
    }
};

/// The second Sobol dimension of `index`: the same bits as sobolSecondBitwise.
inline uint32_t sobolSecond(uint32_t index) {
    static const SobolSecondTables tables;
    return tables.byte[0][index & 255u] ^ tables.byte[1][(index >> 8) & 255u] ^
           tables.byte[2][(index >> 16) & 255u] ^ tables.byte[3][index >> 24];
}

/// A 64-bit mix (SplitMix64 finaliser) folded to 32 bits.
inline uint32_t hash(uint64_t a, uint64_t b) {
    uint64_t z = a * 0x9E3779B97F4A7C15ULL + b + 0x632BE59BD9B4E019ULL;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return static_cast<uint32_t>(z ^ (z >> 32));
}

/// The SplitMix64 finaliser: every input bit reaches every output bit.
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/// [0, 1) from the top 24 bits.
inline float toUnit(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

}  // namespace detail

enum class SamplerType { Independent, Sobol };

/// The scene-file name of each sampler type.
inline const char *samplerName(SamplerType type) { return type == SamplerType::Sobol ? "sobol" : "independent"; }

/// The type called `name`, or nothing.
inline std::optional<SamplerType> parseSampler(const std::string &name) {
    if (name == "independent") return SamplerType::Independent;
    if (name == "sobol") return SamplerType::Sobol;
    return std::nullopt;
}

/// The type a scene file's <sampler type="name"> renders with, or nothing: ours by name, and Mitsuba 3's
/// stratified kinds (stratified, multijitter, orthogonal, ldsampler) as sobol, stratified within a pixel as
/// they are. The expectation of every pixel is the same whichever is used.
inline std::optional<SamplerType> samplerFromFile(const std::string &name) {
    if (name == "stratified" || name == "multijitter" || name == "orthogonal" || name == "ldsampler")
        return SamplerType::Sobol;
    return parseSampler(name);
}

/// Sample values for one pixel of one batch: call startSample(i) for sample i, then next2D()
/// for each 2D dimension pair the integrator needs.
class Sampler {
public:
    Sampler(SamplerType type, uint64_t seed, uint64_t batch, uint64_t pixel)
        : m_type(type), m_key(detail::hash(detail::hash(seed, batch), pixel)),
          m_key64(detail::mix64(detail::mix64(seed * 0x9E3779B97F4A7C15ULL + batch) + pixel)) {}

    /// Starts sample `index` at 2D dimension pair `pair` (1 to skip the pixel jitter already drawn).
    void startSample(uint32_t index, uint32_t pair = 0) {
        m_index = index;
        m_dimension = pair;
    }

    Vec2f next2D() { return sample2D(m_index, m_dimension++); }

    /// The current sample's index (startSample's).
    uint32_t index() const { return m_index; }

    SamplerType type() const { return m_type; }

    /// sample2D of the independent sampler: one 64-bit hash per (sample, pair), 24 bits for each
    /// coordinate. Branch-free, so a packet's lanes compute it in SIMD.
    Vec2f independent2D(uint32_t index, uint32_t pair) const {
        using namespace detail;
        const uint64_t z = mix64(m_key64 + index * 0xD1B54A32D192ED03ULL + pair * 0xABC98388FB8FAC03ULL);
        return {toUnit(static_cast<uint32_t>(z >> 32)), toUnit(static_cast<uint32_t>(z))};
    }

    /// The value of 2D pair `pair` of sample `index`, without moving the sampler: the samples of a
    /// packet each read their own.
    Vec2f sample2D(uint32_t index, uint32_t pair) const {
        using namespace detail;
        if (m_type == SamplerType::Independent) return independent2D(index, pair);
        const uint32_t pairSeed = hash(m_key, pair);
        // Shuffle the order of the points, then scramble each coordinate (Burley 2020). The first
        // Sobol dimension is the bit reversal of the index, so its scramble needs no reversal in.
        const uint32_t i = owenScramble(index, pairSeed);
        const uint32_t x = reverseBits(laineKarras(i, pairSeed ^ 0xA511E9B3u));
        const uint32_t y = owenScramble(sobolSecond(i), pairSeed ^ 0x63D83595u);
        return {toUnit(x), toUnit(y)};
    }

private:
    SamplerType m_type;
    uint32_t m_key;
    uint64_t m_key64;
    uint32_t m_index = 0;
    uint32_t m_dimension = 0;
};

}  // namespace mcval
