/* Mirrors of include/mcval_bsdfs.h with one mistake each, for the delta-lobe checks (harness/bsdfs/delta.py):
 * each must fail the check that names it in tests/bsdfs/test_conductor.py. */
#include <math.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

MCVAL_DECLARE_BSDF(unturned_mirror)
MCVAL_DECLARE_BSDF(conductor)
MCVAL_DECLARE_BSDF(finite_pdf_mirror)

enum Mistake { UNTURNED, NO_FRESNEL, FINITE_PDF };

static void zero(float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = 0.f;
}

static void sample(enum Mistake m, const float *params, const float *wi, const float *u, float *wo, float *weight,
                   float *pdf, size_t n) {
    (void)u;
    for (size_t i = 0; i < n; ++i) {
        const float *v = wi + 3 * i;
        const float turn = m == UNTURNED ? 1.f : -1.f; /* the tangential part must turn around */
        wo[3 * i] = turn * v[0], wo[3 * i + 1] = turn * v[1], wo[3 * i + 2] = v[2];
        if (!(v[2] > 0)) {
            weight[i] = pdf[i] = 0.f;
            continue;
        }
        /* No Fresnel: the specular reflectance alone (Mitsuba's conductor multiplies it by F). */
        weight[i] = m == NO_FRESNEL ? params[2] : 1.f;
        pdf[i] = m == FINITE_PDF ? 1.f : INFINITY; /* Mitsuba's own pdf of a delta sample is 1: not the ABI's */
    }
}

#define DEFINE(NAME, PARAMS, MISTAKE)                                                                           \
    const char *bsdf_##NAME##_params = PARAMS;                                                                  \
    void bsdf_##NAME##_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {   \
        (void)params, (void)wi, (void)wo;                                                                       \
        zero(value, n);                                                                                         \
    }                                                                                                           \
    void bsdf_##NAME##_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {       \
        (void)params, (void)wi, (void)wo;                                                                       \
        zero(out, n);                                                                                           \
    }                                                                                                           \
    void bsdf_##NAME##_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,  \
                              float *pdf, size_t n) {                                                           \
        sample(MISTAKE, params, wi, u, wo, weight, pdf, n);                                                     \
    }

DEFINE(unturned_mirror, "", UNTURNED)
DEFINE(conductor, "eta,k,specular_reflectance", NO_FRESNEL)
DEFINE(finite_pdf_mirror, "", FINITE_PDF)
