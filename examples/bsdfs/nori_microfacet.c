/* Nori's `microfacet` BSDF (the course's PA5), through mcval's BSDF ABI (include/mcval_bsdfs.h): a diffuse base
 * of albedo kd under a Beckmann specular lobe of roughness alpha and weight ks, with the Fresnel reflectance of a
 * dielectric interface (int_ior inside, ext_ior outside). Nori derives ks = 1 - max(kd) from a coloured kd; one
 * gray channel takes kd (its luminance) and ks apart, which is how `bsdfs --nori-test` passes Nori's values:
 *
 *   f(wi, wo) = kd / pi + ks D(h) F(wi . h) G(wi, wo, h) / (4 cos theta_i cos theta_o),   h = (wi + wo) / |wi + wo|
 *
 * D is Beckmann's distribution of normals, G Smith's masking with Walter's rational approximation, as Nori has it.
 * Sampling picks the specular lobe with probability ks (by the third uniform), draws h from D(h) cos theta_h and
 * reflects wi about it, else draws wo cosine-weighted; the pdf is the mixture of the two densities of wo.
 *
 * Build: cc -O2 -shared -fPIC -I include examples/bsdfs/nori_microfacet.c -o libnori_microfacet.so -lm
 * Check: python -m harness bsdfs --bsdf-library libnori_microfacet.so */
#include <math.h>
#include <stddef.h>

#include <mcval_bsdfs.h>

#define PI 3.14159265358979323846f

MCVAL_DECLARE_BSDF(microfacet)

const char *bsdf_microfacet_params = "alpha,kd,ks,int_ior,ext_ior";

typedef struct { float x, y, z; } vec3;

static vec3 load(const float *v, size_t i) { vec3 r = {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; return r; }
static float dot(vec3 a, vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static vec3 half_vector(vec3 a, vec3 b) {
    vec3 h = {a.x + b.x, a.y + b.y, a.z + b.z};
    const float n = sqrtf(dot(h, h));
    h.x /= n, h.y /= n, h.z /= n;
    return h;
}

/* Beckmann's density of normals by projected area. */
static float beckmann_d(vec3 h, float alpha) {
    if (h.z <= 0) return 0.f;
    const float c2 = h.z * h.z, tan2 = (1 - c2) / c2;
    return expf(-tan2 / (alpha * alpha)) / (PI * alpha * alpha * c2 * c2);
}

/* Smith's masking of v by normals h (Walter et al. 2007's rational fit), 0 where v sees their back. */
static float smith_g1(vec3 v, vec3 h, float alpha) {
    if (dot(v, h) / v.z <= 0) return 0.f;
    const float tan_theta = sqrtf(fmaxf(0.f, 1 - v.z * v.z)) / v.z;
    if (tan_theta == 0) return 1.f;
    const float b = 1 / (alpha * tan_theta);
    return b >= 1.6f ? 1.f : (3.535f * b + 2.181f * b * b) / (1 + 2.276f * b + 2.577f * b * b);
}

/* Fresnel reflectance of unpolarised light arriving at cos_i from the side of index eta_i. */
static float fresnel(float cos_i, float eta_i, float eta_t) {
    const float eta = eta_i / eta_t, sin_t2 = eta * eta * fmaxf(0.f, 1 - cos_i * cos_i);
    if (sin_t2 >= 1) return 1.f;
    const float cos_t = sqrtf(1 - sin_t2);
    const float rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    const float rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

static float value(const float *p, vec3 wi, vec3 wo) {
    if (wi.z <= 0 || wo.z <= 0) return 0.f;
    const float alpha = p[0], kd = p[1], ks = p[2];
    const vec3 h = half_vector(wi, wo);
    const float specular = beckmann_d(h, alpha) * fresnel(dot(wi, h), p[4], p[3]) * smith_g1(wi, h, alpha) *
                           smith_g1(wo, h, alpha) / (4 * wi.z * wo.z);
    return (kd / PI + ks * specular) * wo.z;
}

static float density(const float *p, vec3 wi, vec3 wo) {
    if (wi.z <= 0 || wo.z <= 0) return 0.f;
    const float alpha = p[0], ks = p[2];
    const vec3 h = half_vector(wi, wo);
    /* D(h) cos theta_h is h's density; 1 / (4 wo . h) the Jacobian from h to the reflected wo. */
    return ks * beckmann_d(h, alpha) * h.z / (4 * dot(wo, h)) + (1 - ks) * wo.z / PI;
}

void bsdf_microfacet_eval(const float *params, const float *wi, const float *wo, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = value(params, load(wi, i), load(wo, i));
}

void bsdf_microfacet_pdf(const float *params, const float *wi, const float *wo, float *out, size_t n) {
    for (size_t i = 0; i < n; ++i) out[i] = density(params, load(wi, i), load(wo, i));
}

void bsdf_microfacet_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,
                            float *pdf, size_t n) {
    const float alpha = params[0], ks = params[2];
    for (size_t i = 0; i < n; ++i) {
        const vec3 in = load(wi, i);
        const float u1 = u[3 * i], phi = 2 * PI * u[3 * i + 1];
        vec3 out;
        if (u[3 * i + 2] < ks) {  /* a normal from D(h) cos theta_h, then the mirror direction of wi */
            const float tan2 = -alpha * alpha * logf(1 - u1), c = 1 / sqrtf(1 + tan2), s = sqrtf(fmaxf(0.f, 1 - c * c));
            const vec3 h = {s * cosf(phi), s * sinf(phi), c};
            const float d = 2 * dot(in, h);
            out.x = d * h.x - in.x, out.y = d * h.y - in.y, out.z = d * h.z - in.z;
            /* A normal facing away from wi reflects it to a direction whose half vector is -h: the pdf has no
             * such h (its D is 0 below the surface), so this sample must fail, not count as the diffuse lobe's. */
            if (d <= 0) {
                weight[i] = pdf[i] = 0.f;
                continue;
            }
        } else {                  /* cosine-weighted */
            const float r = sqrtf(u1);
            out.x = r * cosf(phi), out.y = r * sinf(phi), out.z = sqrtf(fmaxf(0.f, 1 - u1));
        }
        wo[3 * i] = out.x, wo[3 * i + 1] = out.y, wo[3 * i + 2] = out.z;
        const float p = density(params, in, out);
        if (in.z <= 0 || out.z <= 0 || p <= 0) {
            weight[i] = pdf[i] = 0.f;
            continue;
        }
        pdf[i] = p;
        weight[i] = value(params, in, out) / p;
    }
}
