/* mcval_bsdfs.h: the C ABI through which mcval's BSDF checks reach a library's BSDFs (our renderer's are
 * built as one: build/libmcval_bsdfs.so).
 *
 * A library exports, for each BSDF NAME it offers, these four symbols under these exact (unmangled) names:
 *
 *   bsdf_NAME_params   a `const char *` (a pointer, as MCVAL_DECLARE_BSDF below declares it) to the names of
 *                      its parameters, comma-separated ("alpha,eta", "reflectance", "" for none);
 *                      `params` below holds one float per name, in this order, the same for every row
 *   bsdf_NAME_eval     value = f(wi, wo) |cos theta_o|
 *   bsdf_NAME_pdf      the density of wo by solid angle with which NAME_sample draws it given wi
 *   bsdf_NAME_sample   draws wo from 3 uniforms, with weight = value / pdf and its pdf;
 *                      weight and pdf 0 (wo any unit vector) where nothing is sampled;
 *                      on a delta lobe (a mirror, a smooth glass), pdf = INFINITY and weight the lobe's
 *                      (its reflectance or transmittance at wi over the probability of choosing the lobe);
 *                      eval and pdf are then those of the other lobes only (0 for a pure mirror)
 *
 * Frame and conventions (Mitsuba 3's): the local shading frame, z the shading normal; wi points toward the
 * viewer (where the light goes, Mitsuba's si.wi), wo toward where the light comes from; both unit vectors.
 * A value is one channel (a gray BSDF: the parameters are scalars).
 *
 * wi below the surface (z < 0): a BSDF that only reflects returns value, pdf, weight 0 there (Mitsuba's
 * convention); one that transmits (a glass) is asked from both sides.
 *
 * Layout: float32, n rows per call, 3-vectors interleaved (x0, y0, z0, x1, ...); u holds 3 uniforms a row
 * in [0, 1), to use as the BSDF likes (e.g. the first to choose a lobe and, rescaled, to draw in it; the checks
 * only ask that the three be all it draws from); value, weight and pdf one float a row.
 * The harness calls them from one thread, with n up to 2^22; they must not keep the pointers.
 */
#ifndef MCVAL_BSDFS_H
#define MCVAL_BSDFS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The four functions of one BSDF, declared for NAME: MCVAL_DECLARE_BSDF(diffuse) declares bsdf_diffuse_params,
 * bsdf_diffuse_eval, bsdf_diffuse_pdf and bsdf_diffuse_sample. Put it before their definitions: the compiler
 * then refuses a definition of another type (e.g. `const char bsdf_diffuse_params[]`, an array, where the ABI
 * has a pointer). */
#define MCVAL_DECLARE_BSDF(NAME)                                                                            \
    extern const char *bsdf_##NAME##_params;                                                               \
    void bsdf_##NAME##_eval(const float *params, const float *wi, const float *wo, float *value, size_t n);  \
    void bsdf_##NAME##_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n);    \
    void bsdf_##NAME##_sample(const float *params, const float *wi, const float *u, float *wo, float *weight, \
                              float *pdf, size_t n);

#ifdef __cplusplus
}
#endif

#endif /* MCVAL_BSDFS_H */
