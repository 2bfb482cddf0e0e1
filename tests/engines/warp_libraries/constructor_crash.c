/* A warp library whose constructor segfaults when it is loaded: every warp of it fails, none is judged. */
#include <stddef.h>
#include "mcval_warps.h"

__attribute__((constructor)) static void crash_on_load(void) {
    volatile int *volatile nowhere = NULL;  /* volatile twice: the compiler may drop neither */
    *nowhere = 1;
}

void square_to_uniform_square(const float *u, float *out, size_t n) { for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i]; }
void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n) { (void)p; for (size_t i = 0; i < n; ++i) pdf[i] = 1.0f; }
void square_to_tent(const float *u, float *out, size_t n) { for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i]; }
void square_to_tent_pdf(const float *p, float *pdf, size_t n) { (void)p; for (size_t i = 0; i < n; ++i) pdf[i] = 1.0f; }
