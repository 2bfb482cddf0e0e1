/* Smooth dielectrics of include/mcval_bsdfs.h with one mistake each, for the delta-lobe and energy checks: each
 * must fail the check that names it in tests/bsdfs/test_dielectric.py. Parameters: int_ior, ext_ior. */
#include <math.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

MCVAL_DECLARE_BSDF(dielectric)
MCVAL_DECLARE_BSDF(snell_inverted)

enum Mistake { NO_RADIANCE_SCALE, ETA_INVERTED };

/* Fresnel reflectance at cos_i (negative from inside), the refracted cosine's size and eta_ti (wi's side over
 * the far side's), as Mitsuba's fresnel(). */
static float fresnel(float cos_i, float eta, float *cos_t, float *eta_ti) {
    const int outside = cos_i >= 0;
    const float eta_it = outside ? eta : 1 / eta;
    *eta_ti = 1 / eta_it;
    const float c = fabsf(cos_i), t2 = 1 - (1 - c * c) * *eta_ti * *eta_ti;
    *cos_t = sqrtf(fmaxf(t2, 0.f));
    if (c == 0) return 1.f;
    const float as = (c - eta_it * *cos_t) / (c + eta_it * *cos_t), ap = (*cos_t - eta_it * c) / (*cos_t + eta_it * c);
    return 0.5f * (as * as + ap * ap);
}

static void zero(float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = 0.f;
}

static void sample(enum Mistake m, const float *params, const float *wi, const float *u, float *wo, float *weight,
                   float *pdf, size_t n) {
    const float eta = params[0] / params[1];
    for (size_t i = 0; i < n; ++i) {
        const float *v = wi + 3 * i;
        float cos_t, eta_ti;
        const float r = fresnel(v[2], eta, &cos_t, &eta_ti);
        pdf[i] = INFINITY;
        if (u[3 * i] <= r) {
            wo[3 * i] = -v[0], wo[3 * i + 1] = -v[1], wo[3 * i + 2] = v[2];
            weight[i] = 1.f;
            continue;
        }
        /* ETA_INVERTED bends by eta_it where eta_ti belongs (a unit vector still, its cosine from its sine). */
        if (m == ETA_INVERTED)
            cos_t = sqrtf(fmaxf(0.f, 1 - (v[0] * v[0] + v[1] * v[1]) / (eta_ti * eta_ti))), eta_ti = 1 / eta_ti;
        wo[3 * i] = -eta_ti * v[0], wo[3 * i + 1] = -eta_ti * v[1], wo[3 * i + 2] = v[2] >= 0 ? -cos_t : cos_t;
        /* NO_RADIANCE_SCALE leaves out eta_ti^2, the compression of radiance into the far side's solid angle. */
        weight[i] = m == NO_RADIANCE_SCALE ? 1.f : m == ETA_INVERTED ? 1 / (eta_ti * eta_ti) : eta_ti * eta_ti;
    }
}

#define DEFINE(NAME, MISTAKE)                                                                                   \
    const char *bsdf_##NAME##_params = "int_ior,ext_ior";                                                       \
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

DEFINE(dielectric, NO_RADIANCE_SCALE)
DEFINE(snell_inverted, ETA_INVERTED)
