/* BSDFs of include/mcval_bsdfs.h whose lobes are deltas (mirrors, smooth glass), and a plastic, each with one
 * mistake, for the delta-lobe, energy and reference checks: each must fail the check that names it in
 * tests/bsdfs/test_conductor.py, test_dielectric.py and test_plastic.py. */
#include <math.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

MCVAL_DECLARE_BSDF(unturned_mirror)
MCVAL_DECLARE_BSDF(conductor)
MCVAL_DECLARE_BSDF(finite_pdf_mirror)
MCVAL_DECLARE_BSDF(dielectric)
MCVAL_DECLARE_BSDF(snell_inverted)

enum Mistake { UNTURNED, NO_FRESNEL, FINITE_PDF, NO_RADIANCE_SCALE, ETA_INVERTED };

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

static void mirror_sample(enum Mistake m, const float *params, const float *wi, const float *u, float *wo,
                          float *weight, float *pdf, size_t n) {
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

static void glass_sample(enum Mistake m, const float *params, const float *wi, const float *u, float *wo,
                         float *weight, float *pdf, size_t n) {
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

static void sample(enum Mistake m, const float *params, const float *wi, const float *u, float *wo, float *weight,
                   float *pdf, size_t n) {
    (m == NO_RADIANCE_SCALE || m == ETA_INVERTED ? glass_sample : mirror_sample)(m, params, wi, u, wo, weight, pdf, n);
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
DEFINE(dielectric, "int_ior,ext_ior", NO_RADIANCE_SCALE)
DEFINE(snell_inverted, "int_ior,ext_ior", ETA_INVERTED)

/* Mitsuba's plastic (linear, gray) without the 1 / eta^2 by which light leaving the coating spreads into a
 * larger solid angle: its diffuse lobe 2.25 times too bright for eta 1.5. */
MCVAL_DECLARE_BSDF(plastic)
const char *bsdf_plastic_params = "int_ior,ext_ior,diffuse_reflectance,nonlinear";

#define PI 3.14159265358979323846f

static float plastic_specular_probability(const float *params, float cos_i) {
    float cos_t, eta_ti;
    const float r = fresnel(cos_i, params[0] / params[1], &cos_t, &eta_ti), w = 1 / (params[2] + 1);
    return r * w / (r * w + (1 - r) * (1 - w));
}

static float plastic_diffuse(const float *params, float cos_i, float cos_o) {
    const float eta = params[0] / params[1], inv = eta; /* 1 / (1 / eta): the internal side's fit */
    const float fdr = -1.4399f / (inv * inv) + 0.7099f / inv + 0.6681f + 0.0636f * inv;
    float cos_t, eta_ti;
    const float ti = 1 - fresnel(cos_i, eta, &cos_t, &eta_ti), to = 1 - fresnel(cos_o, eta, &cos_t, &eta_ti);
    return params[2] / (1 - fdr) / PI * cos_o * ti * to; /* the mistake: no 1 / eta^2 */
}

void bsdf_plastic_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {
    for (size_t i = 0; i < n; ++i)
        value[i] = wi[3 * i + 2] > 0 && wo[3 * i + 2] > 0 ? plastic_diffuse(params, wi[3 * i + 2], wo[3 * i + 2]) : 0.f;
}

void bsdf_plastic_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i)
        out[i] = wi[3 * i + 2] > 0 && wo[3 * i + 2] > 0
                     ? (1 - plastic_specular_probability(params, wi[3 * i + 2])) * wo[3 * i + 2] / PI : 0.f;
}

void bsdf_plastic_sample(const float *params, const float *wi, const float *u, float *wo, float *weight, float *pdf,
                         size_t n) {
    for (size_t i = 0; i < n; ++i) {
        const float *v = wi + 3 * i, cos_i = v[2];
        wo[3 * i] = wo[3 * i + 1] = 0.f, wo[3 * i + 2] = 1.f;
        weight[i] = pdf[i] = 0.f;
        if (!(cos_i > 0)) continue;
        const float p = plastic_specular_probability(params, cos_i);
        if (u[3 * i + 2] < p) { /* the third uniform chooses the lobe */
            float cos_t, eta_ti;
            wo[3 * i] = -v[0], wo[3 * i + 1] = -v[1], wo[3 * i + 2] = cos_i;
            weight[i] = fresnel(cos_i, params[0] / params[1], &cos_t, &eta_ti) / p;
            pdf[i] = INFINITY;
            continue;
        }
        const float r = sqrtf(u[3 * i]), phi = 2 * PI * u[3 * i + 1], z = sqrtf(fmaxf(0.f, 1 - u[3 * i]));
        if (!(z > 0)) continue;
        wo[3 * i] = r * cosf(phi), wo[3 * i + 1] = r * sinf(phi), wo[3 * i + 2] = z;
        pdf[i] = (1 - p) * z / PI;
        weight[i] = plastic_diffuse(params, cos_i, z) / pdf[i];
    }
}
