/* A warp library that misbehaves one way per warp, for tests/engines/test_warp_library.py: each must cost only
 * its own row. square_to_uniform_square is correct, and prints to stdout on every call. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include "mcval_warps.h"

static void fill(float *out, size_t count) { for (size_t i = 0; i < count; ++i) out[i] = 0.5f; }
static void ones(float *pdf, size_t n) { for (size_t i = 0; i < n; ++i) pdf[i] = 1.0f; }

void square_to_uniform_square(const float *u, float *out, size_t n) {
    printf("uniform square: %zu samples\n", n);  /* on fd 1: must not reach the harness's answers */
    fflush(stdout);
    for (size_t i = 0; i < 2 * n; ++i) out[i] = u[i];
}
void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i)
        pdf[i] = (p[2*i] >= 0 && p[2*i] <= 1 && p[2*i+1] >= 0 && p[2*i+1] <= 1) ? 1.0f : 0.0f;
}

void square_to_tent(const float *u, float *out, size_t n) {  /* a segfault */
    (void)u; (void)n;
    volatile float *volatile nowhere = NULL;
    out[0] = *nowhere;
}
void square_to_tent_pdf(const float *p, float *pdf, size_t n) { (void)p; ones(pdf, n); }

void square_to_uniform_disk(const float *u, float *out, size_t n) { (void)u; (void)out; (void)n; abort(); }
void square_to_uniform_disk_pdf(const float *p, float *pdf, size_t n) { (void)p; ones(pdf, n); }

void square_to_uniform_sphere(const float *u, float *out, size_t n) {  /* 3n floats, and 8 more */
    (void)u;
    fill(out, 3 * n + 8);
}
void square_to_uniform_sphere_pdf(const float *p, float *pdf, size_t n) { (void)p; ones(pdf, n); }

void square_to_uniform_hemisphere(const float *u, float *out, size_t n) { (void)u; (void)out; (void)n; exit(0); }
void square_to_uniform_hemisphere_pdf(const float *p, float *pdf, size_t n) { (void)p; ones(pdf, n); }

void square_to_cosine_hemisphere(const float *u, float *out, size_t n) {  /* a loop that ignores SIGTERM */
    (void)u;
    signal(SIGTERM, SIG_IGN);
    for (volatile size_t i = 0;; ++i) out[i % (3 * n)] = 0.0f;
}
void square_to_cosine_hemisphere_pdf(const float *p, float *pdf, size_t n) { (void)p; ones(pdf, n); }
