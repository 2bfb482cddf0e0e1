/* A BSDF whose sampler never returns: the checks kill its process at the time limit and fail its rows. */
#include <stddef.h>
#include <unistd.h>

#include <mcval_bsdfs.h>

MCVAL_DECLARE_BSDF(hang)

const char *bsdf_hang_params = "";
void bsdf_hang_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    (void)params, (void)wi, (void)wo;
    for (size_t i = 0; i < n; ++i) value[i] = 0.f;
}
void bsdf_hang_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {
    (void)params, (void)wi, (void)wo;
    for (size_t i = 0; i < n; ++i) pdf[i] = 0.f;
}
void bsdf_hang_sample(const float *params, const float *wi, const float *u, float *wo, float *weight, float *pdf,
                      size_t n) {
    (void)params, (void)wi, (void)u, (void)wo, (void)weight, (void)pdf, (void)n;
    for (;;) sleep(1);
}
