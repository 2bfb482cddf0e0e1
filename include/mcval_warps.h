/* mcval_warps.h: the C ABI through which `python -m harness warps --warp-library LIB.so` checks a library's
 * sample warps against their pdfs (and against Mitsuba 3's).
 *
 * A library exports any subset of these functions, under these exact (unmangled) names; the warp matrix
 * runs on the warps it exports. A sampler exported without its pdf fails its row with that reason.
 *
 * Layout: float32, interleaved, n entries per call.
 *   u:   n uniforms (u0, u1, u0, u1, ...), each in [0, 1); only the hard-input check passes u = 1.
 *   out: n points, 2 floats each (square, tent, disk) or 3 (sphere, hemisphere, Beckmann: directions).
 *   p:   n points as a pdf takes them, in the same layout as the sampler writes them.
 *   pdf: n densities: with respect to area on [0,1]^2, [-1,1]^2 and the unit disk, and to solid angle on
 *        the sphere and the hemisphere (z up); 0 outside the warp's domain.
 * Beckmann's functions take the roughness alpha (the slope standard deviation times sqrt 2) last; its pdf is
 * D(m) cos(theta_m), the density of the microfacet normal m.
 *
 * The harness calls them from one thread, with n up to 2^22; they must not keep the pointers.
 */
#ifndef MCVAL_WARPS_H
#define MCVAL_WARPS_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

void square_to_uniform_square(const float *u, float *out, size_t n);
void square_to_uniform_square_pdf(const float *p, float *pdf, size_t n);

void square_to_tent(const float *u, float *out, size_t n);
void square_to_tent_pdf(const float *p, float *pdf, size_t n);

void square_to_uniform_disk(const float *u, float *out, size_t n);
void square_to_uniform_disk_pdf(const float *p, float *pdf, size_t n);

void square_to_uniform_sphere(const float *u, float *out, size_t n);
void square_to_uniform_sphere_pdf(const float *p, float *pdf, size_t n);

void square_to_uniform_hemisphere(const float *u, float *out, size_t n);
void square_to_uniform_hemisphere_pdf(const float *p, float *pdf, size_t n);

void square_to_cosine_hemisphere(const float *u, float *out, size_t n);
void square_to_cosine_hemisphere_pdf(const float *p, float *pdf, size_t n);

void square_to_beckmann(const float *u, float *out, size_t n, float alpha);
void square_to_beckmann_pdf(const float *p, float *pdf, size_t n, float alpha);

#ifdef __cplusplus
}
#endif

#endif /* MCVAL_WARPS_H */
