// A float's bits and back, without undefined behaviour (memcpy, which compiles to a register move and
// vectorises in a loop over lanes).
#pragma once

#include <cstdint>
#include <cstring>

namespace mcval::detail {

inline float bitsToFloat(uint32_t b) {
    float f;
    std::memcpy(&f, &b, sizeof f);
    return f;
}

inline uint32_t floatToBits(float f) {
    uint32_t b;
    std::memcpy(&b, &f, sizeof b);
    return b;
}

}  // namespace mcval::detail
