/* BSDFs of include/mcval_bsdfs.h for the tests of harness/engines/bsdf_library.py: one correct, the others
 * each failing in one way (a crash, a write past its output, a function missing). */
#include <math.h>
#include <signal.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

#define PI 3.14159265358979323846f

MCVAL_DECLARE_BSDF(lambert)
MCVAL_DECLARE_BSDF(crash)
MCVAL_DECLARE_BSDF(overrun)

const char *bsdf_lambert_params = "albedo";

void bsdf_lambert_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    for (size_t i = 0; i < n; ++i)
        value[i] = wi[3 * i + 2] > 0 && wo[3 * i + 2] > 0 ? params[0] / PI * wo[3 * i + 2] : 0.f;
}

void bsdf_lambert_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {
    (void)params;
    for (size_t i = 0; i < n; ++i) pdf[i] = wi[3 * i + 2] > 0 && wo[3 * i + 2] > 0 ? wo[3 * i + 2] / PI : 0.f;
}

void bsdf_lambert_sample(const float *params, const float *wi, const float *u, float *wo, float *weight, float *pdf,
                         size_t n) {
    for (size_t i = 0; i < n; ++i) {
        const float r = sqrtf(u[3 * i]), phi = 2 * PI * u[3 * i + 1];
        const float z = sqrtf(fmaxf(0.f, 1 - u[3 * i]));
        wo[3 * i] = r * cosf(phi), wo[3 * i + 1] = r * sinf(phi), wo[3 * i + 2] = z;
        const int ok = wi[3 * i + 2] > 0 && z > 0;
        weight[i] = ok ? params[0] : 0.f;
        pdf[i] = ok ? z / PI : 0.f;
    }
}

/* Evaluates as lambert does; its sampler dereferences a null pointer. */
const char *bsdf_crash_params = "";
void bsdf_crash_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    bsdf_lambert_eval(params, wi, wo, value, n);
}
void bsdf_crash_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {
    bsdf_lambert_pdf(params, wi, wo, pdf, n);
}
void bsdf_crash_sample(const float *params, const float *wi, const float *u, float *wo, float *weight, float *pdf,
                       size_t n) {
    (void)params, (void)wi, (void)u, (void)wo, (void)weight, (void)pdf, (void)n;
    raise(SIGSEGV);
}

/* Its eval writes one value more than it was asked for, past the end of the output. */
const char *bsdf_overrun_params = "albedo";
void bsdf_overrun_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    bsdf_lambert_eval(params, wi, wo, value, n);
    value[n] = 1.f;
}
void bsdf_overrun_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {
    bsdf_lambert_pdf(params, wi, wo, pdf, n);
}
void bsdf_overrun_sample(const float *params, const float *wi, const float *u, float *wo, float *weight, float *pdf,
                         size_t n) {
    bsdf_lambert_sample(params, wi, u, wo, weight, pdf, n);
}

/* Exports its parameters, eval and pdf, but no sampler. */
const char *bsdf_partial_params = "albedo";
void bsdf_partial_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    bsdf_lambert_eval(params, wi, wo, value, n);
}
void bsdf_partial_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {
    bsdf_lambert_pdf(params, wi, wo, pdf, n);
}

/* Parameter lists a user writes without the header's declaration, each a Lambertian otherwise: an array (read as
 * the string it holds), names separated by a space, a trailing comma, a NULL pointer (the last three refused). */
#define LAMBERT_WRAPPERS(NAME)                                                                                  \
    void bsdf_##NAME##_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {   \
        bsdf_lambert_eval(params, wi, wo, value, n);                                                            \
    }                                                                                                           \
    void bsdf_##NAME##_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {       \
        bsdf_lambert_pdf(params, wi, wo, pdf, n);                                                               \
    }                                                                                                           \
    void bsdf_##NAME##_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,  \
                              float *pdf, size_t n) {                                                           \
        bsdf_lambert_sample(params, wi, u, wo, weight, pdf, n);                                                 \
    }
const char bsdf_arrayed_params[] = "albedo";
LAMBERT_WRAPPERS(arrayed)
const char *bsdf_spaced_params = "albedo exponent";
LAMBERT_WRAPPERS(spaced)
const char *bsdf_trailing_params = "albedo,";
LAMBERT_WRAPPERS(trailing)
const char *bsdf_nullparams_params = 0;
LAMBERT_WRAPPERS(nullparams)
