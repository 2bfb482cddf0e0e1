// MCVAL_HOT marks the per-sample loops: GCC compiles each twice more, for AVX-512 (x86-64-v4) and
// AVX2 (x86-64-v3) machines, beside the baseline x86-64 code, and the loader picks the one this CPU
// runs (an ifunc). One binary is fast here and still runs on any x86-64 machine.
#pragma once

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(MCVAL_NO_CLONES)
#define MCVAL_HOT __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define MCVAL_HOT
#endif
