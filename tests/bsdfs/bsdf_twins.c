/* A Lambertian BSDF of include/mcval_bsdfs.h and its known-wrong twins, each with one mistake a renderer's
 * author makes, for the tests of harness/bsdfs/checks.py (each must fail the check that names it). */
#include <math.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

#define PI 3.14159265358979323846f

MCVAL_DECLARE_BSDF(lambert)
MCVAL_DECLARE_BSDF(no_inv_pi)
MCVAL_DECLARE_BSDF(weight_no_cosine)
MCVAL_DECLARE_BSDF(uniform_pdf)
MCVAL_DECLARE_BSDF(one_sided_shadowing)
MCVAL_DECLARE_BSDF(nan_on_the_normal)
MCVAL_DECLARE_BSDF(unguarded_sampler)

/* The mistakes, as factors of the correct value, weight and pdf. */
enum Mistake { NONE, NO_INV_PI, WEIGHT_NO_COSINE, UNIFORM_PDF, ONE_SIDED_SHADOWING, NAN_ON_THE_NORMAL, UNGUARDED };

static int above(const float *w, size_t i) { return w[3 * i + 2] > 0; }

/* A shadowing-like factor of the outgoing direction alone: applied on one side, it breaks reciprocity. */
static float g1(float cos_o) { return 0.5f + 0.5f * cos_o; }

static float value(enum Mistake m, float albedo, float cos_o) {
    const float v = (m == NO_INV_PI ? albedo : albedo / PI) * cos_o;
    return m == ONE_SIDED_SHADOWING ? v * g1(cos_o) : v;
}

static float density(enum Mistake m, float cos_o) { return m == UNIFORM_PDF ? 1 / (2 * PI) : cos_o / PI; }

/* 1, as the squared cosine and sine of wi's azimuth add up, but 0 / 0 where wi is on the normal. */
static float azimuth_norm(const float *wi, size_t i) {
    const float s = sqrtf(1 - wi[3 * i + 2] * wi[3 * i + 2]), c = wi[3 * i] / s, d = wi[3 * i + 1] / s;
    return c * c + d * d;
}

static void eval(enum Mistake m, const float *params, const float *wi, const float *wo, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        out[i] = above(wi, i) && above(wo, i) ? value(m, params[0], wo[3 * i + 2]) : 0.f;
        if (m == NAN_ON_THE_NORMAL) out[i] *= azimuth_norm(wi, i);
    }
}

static void pdf(enum Mistake m, const float *wi, const float *wo, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = above(wi, i) && above(wo, i) ? density(m, wo[3 * i + 2]) : 0.f;
}

/* Cosine-weighted sampling for all (the uniform_pdf twin's pdf says otherwise). */
static void sample(enum Mistake m, const float *params, const float *wi, const float *u, float *wo, float *weight,
                   float *pdf_out, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        float r = sqrtf(u[3 * i]), z = sqrtf(fmaxf(0.f, 1 - u[3 * i]));
        if (m == UNGUARDED) { /* z^2 uniform as well, but z = 0 at u = 0, where value / pdf is 0 / 0 */
            const float t = r;
            r = z, z = t;
        }
        const float phi = 2 * PI * u[3 * i + 1];
        wo[3 * i] = r * cosf(phi), wo[3 * i + 1] = r * sinf(phi), wo[3 * i + 2] = z;
        if (!(above(wi, i) && (z > 0 || m == UNGUARDED))) {
            weight[i] = pdf_out[i] = 0.f;
            continue;
        }
        pdf_out[i] = density(m, z);
        weight[i] = m == WEIGHT_NO_COSINE ? params[0] / z : value(m, params[0], z) / pdf_out[i];
    }
}

#define DEFINE(NAME, MISTAKE)                                                                                   \
    const char *bsdf_##NAME##_params = "albedo";                                                                \
    void bsdf_##NAME##_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {   \
        eval(MISTAKE, params, wi, wo, value, n);                                                                \
    }                                                                                                           \
    void bsdf_##NAME##_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {       \
        (void)params;                                                                                           \
        pdf(MISTAKE, wi, wo, out, n);                                                                           \
    }                                                                                                           \
    void bsdf_##NAME##_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,  \
                              float *pdf, size_t n) {                                                           \
        sample(MISTAKE, params, wi, u, wo, weight, pdf, n);                                                     \
    }

DEFINE(lambert, NONE)
DEFINE(no_inv_pi, NO_INV_PI)
DEFINE(weight_no_cosine, WEIGHT_NO_COSINE)
DEFINE(uniform_pdf, UNIFORM_PDF)
DEFINE(one_sided_shadowing, ONE_SIDED_SHADOWING)
DEFINE(nan_on_the_normal, NAN_ON_THE_NORMAL)
DEFINE(unguarded_sampler, UNGUARDED)

/* A Lambertian BSDF with a roughness that changes nothing, but divides exp(-1 / alpha^2) by itself: 0 / 0 once
 * alpha is small enough (1e-4) for it to underflow, as a Beckmann term computed apart does. */
MCVAL_DECLARE_BSDF(rough_lambert)
const char *bsdf_rough_lambert_params = "albedo,alpha";

static float underflow_ratio(float alpha) {
    const float e = expf(-1 / (alpha * alpha));
    return e / e;
}

void bsdf_rough_lambert_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    eval(NONE, params, wi, wo, value, n);
    for (size_t i = 0; i < n; ++i) value[i] *= underflow_ratio(params[1]);
}

void bsdf_rough_lambert_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {
    (void)params;
    pdf(NONE, wi, wo, out, n);
}

void bsdf_rough_lambert_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,
                               float *pdf_out, size_t n) {
    sample(NONE, params, wi, u, wo, weight, pdf_out, n);
}

/* A BSDF that draws nothing: value and pdf 0 everywhere, every sample failed. Each check alone would find
 * nothing wrong in it; the matrix must not call that a pass. */
MCVAL_DECLARE_BSDF(draws_nothing)
const char *bsdf_draws_nothing_params = "albedo";

void bsdf_draws_nothing_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    (void)params, (void)wi, (void)wo;
    for (size_t i = 0; i < n; ++i) value[i] = 0.f;
}

void bsdf_draws_nothing_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {
    bsdf_draws_nothing_eval(params, wi, wo, out, n);
}

void bsdf_draws_nothing_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,
                               float *pdf_out, size_t n) {
    (void)params, (void)wi, (void)u;
    for (size_t i = 0; i < n; ++i) {
        wo[3 * i] = wo[3 * i + 1] = 0.f, wo[3 * i + 2] = 1.f;
        weight[i] = pdf_out[i] = 0.f;
    }
}
