/* A Beckmann microfacet reflector of include/mcval_bsdfs.h (no Fresnel: a perfect conductor) and its known-wrong
 * twins, each with one mistake a renderer's author makes in the microfacet model, for tests/bsdfs/test_checks.py:
 *
 *   f(wi, wo) = D(h) G1(wi) G1(wo) / (4 cos theta_i cos theta_o),   sampled by h from D(h) cos theta_h,
 *   pdf(wo) = D(h) cos theta_h / (4 |wo . h|)
 *
 * The twins compute weight = value / pdf from their own value and pdf, so the weight check holds for all: what
 * names each mistake is where the drawn directions and the pdf part ways. */
#include <math.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

#define PI 3.14159265358979323846f

MCVAL_DECLARE_BSDF(beckmann)
MCVAL_DECLARE_BSDF(alpha_for_alpha2)
MCVAL_DECLARE_BSDF(no_jacobian)
MCVAL_DECLARE_BSDF(ggx_sampled)

enum Mistake { NONE, ALPHA_FOR_ALPHA2, NO_JACOBIAN, GGX_SAMPLED };

typedef struct { float x, y, z; } vec3;

static vec3 load(const float *v, size_t i) { vec3 r = {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; return r; }
static float dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static vec3 half_vector(vec3 a, vec3 b) {
    vec3 h = {a.x + b.x, a.y + b.y, a.z + b.z};
    const float n = sqrtf(dot(h, h));
    h.x /= n, h.y /= n, h.z /= n;
    return h;
}

/* Beckmann's D; the ALPHA_FOR_ALPHA2 twin writes alpha where alpha^2 belongs (in its value and pdf, not in its
 * sampler, which draws the true alpha's normals). */
static float beckmann_d(enum Mistake m, vec3 h, float alpha) {
    if (h.z <= 0) return 0.f;
    const float a2 = m == ALPHA_FOR_ALPHA2 ? alpha : alpha * alpha, c2 = h.z * h.z, tan2 = (1 - c2) / c2;
    return expf(-tan2 / a2) / (PI * a2 * c2 * c2);
}

static float smith_g1(vec3 v, vec3 h, float alpha) {
    if (dot(v, h) / v.z <= 0) return 0.f;
    const float tan_theta = sqrtf(fmaxf(0.f, 1 - v.z * v.z)) / v.z;
    if (tan_theta == 0) return 1.f;
    const float b = 1 / (alpha * tan_theta);
    return b >= 1.6f ? 1.f : (3.535f * b + 2.181f * b * b) / (1 + 2.276f * b + 2.577f * b * b);
}

static float value(enum Mistake m, float alpha, vec3 wi, vec3 wo) {
    if (wi.z <= 0 || wo.z <= 0) return 0.f;
    const vec3 h = half_vector(wi, wo);
    return beckmann_d(m, h, alpha) * smith_g1(wi, h, alpha) * smith_g1(wo, h, alpha) / (4 * wi.z);
}

static float density(enum Mistake m, float alpha, vec3 wi, vec3 wo) {
    if (wi.z <= 0 || wo.z <= 0) return 0.f;
    const vec3 h = half_vector(wi, wo);
    const float jacobian = m == NO_JACOBIAN ? 1.f : 1 / (4 * dot(wo, h));  /* dh / dwo of the reflection */
    return beckmann_d(m, h, alpha) * h.z * jacobian;
}

static void sample(enum Mistake m, float alpha, const float *wi, const float *u, float *wo, float *weight,
                   float *pdf, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        const vec3 in = load(wi, i);
        const float u1 = u[3 * i], phi = 2 * PI * u[3 * i + 1];
        /* tan^2 theta_h of Beckmann's normals, or of GGX's for the twin that samples one and evaluates the other */
        const float tan2 = m == GGX_SAMPLED ? alpha * alpha * u1 / (1 - u1) : -alpha * alpha * logf(1 - u1);
        const float c = 1 / sqrtf(1 + tan2), s = sqrtf(fmaxf(0.f, 1 - c * c));
        const vec3 h = {s * cosf(phi), s * sinf(phi), c};
        const float d = 2 * dot(in, h);
        const vec3 out = {d * h.x - in.x, d * h.y - in.y, d * h.z - in.z};
        wo[3 * i] = out.x, wo[3 * i + 1] = out.y, wo[3 * i + 2] = out.z;
        const float p = density(m, alpha, in, out);
        if (in.z <= 0 || out.z <= 0 || d <= 0 || !(p > 0)) {
            weight[i] = pdf[i] = 0.f;
            continue;
        }
        pdf[i] = p;
        weight[i] = value(m, alpha, in, out) / p;
    }
}

#define DEFINE(NAME, MISTAKE)                                                                                   \
    const char *bsdf_##NAME##_params = "alpha";                                                                 \
    void bsdf_##NAME##_eval(const float *params, const float *wi, const float *wo, float *out, size_t n) {     \
        for (size_t i = 0; i < n; ++i) out[i] = value(MISTAKE, params[0], load(wi, i), load(wo, i));            \
    }                                                                                                           \
    void bsdf_##NAME##_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {       \
        for (size_t i = 0; i < n; ++i) out[i] = density(MISTAKE, params[0], load(wi, i), load(wo, i));          \
    }                                                                                                           \
    void bsdf_##NAME##_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,  \
                              float *pdf, size_t n) {                                                           \
        sample(MISTAKE, params[0], wi, u, wo, weight, pdf, n);                                                  \
    }

DEFINE(beckmann, NONE)
DEFINE(alpha_for_alpha2, ALPHA_FOR_ALPHA2)
DEFINE(no_jacobian, NO_JACOBIAN)
DEFINE(ggx_sampled, GGX_SAMPLED)
