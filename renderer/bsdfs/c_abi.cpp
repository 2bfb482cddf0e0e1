// Our BSDFs through the C ABI of include/mcval_bsdfs.h (build/libmcval_bsdfs.so): the BSDF checks load it
// as they load a user's library, so ours and theirs take one path.
#include <mcval_bsdfs.h>

#include <type_traits>
#include <utility>

#include "conductor.h"
#include "dielectric.h"
#include "diffuse.h"
#include "nori_microfacet.h"
#include "plastic.h"
#include "roughconductor.h"
#include "roughdielectric.h"
#include "roughplastic.h"

namespace mcval {
namespace {

Vec3f row(const float *v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

/// A gray BSDF's one channel (its parameters are scalars, so every channel is alike).
float gray(const Color &c) { return c.x; }

template <typename Make>
void evalRows(Make make, const float *params, const float *wi, const float *wo, float *value, size_t n) {
    const auto bsdf = make(params);
    for (size_t i = 0; i < n; ++i) value[i] = gray(bsdf.eval(row(wi, i), row(wo, i)));
}

template <typename Make>
void pdfRows(Make make, const float *params, const float *wi, const float *wo, float *pdf, size_t n) {
    const auto bsdf = make(params);
    for (size_t i = 0; i < n; ++i) pdf[i] = bsdf.pdf(row(wi, i), row(wo, i));
}

/// Whether a BSDF takes the third uniform to choose its lobe (Mitsuba's sample1): sample(wi, u, uLobe).
template <typename B, typename = void>
struct TakesLobeUniform : std::false_type {};
template <typename B>
struct TakesLobeUniform<B, std::void_t<decltype(std::declval<const B &>().sample(Vec3f(), Vec2f(), 0.f))>>
    : std::true_type {};

template <typename Make>
void sampleRows(Make make, const float *params, const float *wi, const float *u, float *wo, float *weight, float *pdf,
                size_t n) {
    const auto bsdf = make(params);
    for (size_t i = 0; i < n; ++i) {
        const Vec2f u2(u[3 * i], u[3 * i + 1]);
        BsdfSample s;
        if constexpr (TakesLobeUniform<std::decay_t<decltype(bsdf)>>::value)
            s = bsdf.sample(row(wi, i), u2, u[3 * i + 2]);
        else
            s = bsdf.sample(row(wi, i), u2);
        wo[3 * i] = s.wo.x, wo[3 * i + 1] = s.wo.y, wo[3 * i + 2] = s.wo.z;
        weight[i] = gray(s.weight);
        pdf[i] = s.pdf;
    }
}

DiffuseBsdf makeDiffuse(const float *params) { return DiffuseBsdf(Color(params[0], params[0], params[0])); }

/// eta, k, specular_reflectance.
ConductorBsdf makeConductor(const float *params) {
    return ConductorBsdf(params[0], params[1], Color(params[2], params[2], params[2]));
}

/// int_ior, ext_ior.
DielectricBsdf makeDielectric(const float *params) { return DielectricBsdf(params[0], params[1]); }

/// int_ior, ext_ior, diffuse_reflectance, nonlinear (0 or 1).
PlasticBsdf makePlastic(const float *params) {
    return PlasticBsdf(params[0], params[1], Color(params[2], params[2], params[2]), params[3] != 0.f);
}

/// alpha, eta, k, ggx (0: Beckmann, 1: GGX), sample_visible (0 or 1).
RoughConductorBsdf makeRoughConductor(const float *params) {
    const auto type = params[3] != 0.f ? MicrofacetDistribution::Type::GGX : MicrofacetDistribution::Type::Beckmann;
    return RoughConductorBsdf(MicrofacetDistribution(type, params[0], params[4] != 0.f), params[1], params[2],
                              Color(1.f, 1.f, 1.f));
}

/// alpha, int_ior, ext_ior, ggx (0: Beckmann, 1: GGX), sample_visible (0 or 1).
RoughDielectricBsdf makeRoughDielectric(const float *params) {
    const auto type = params[3] != 0.f ? MicrofacetDistribution::Type::GGX : MicrofacetDistribution::Type::Beckmann;
    return RoughDielectricBsdf(MicrofacetDistribution(type, params[0], params[4] != 0.f), params[1], params[2]);
}

/// alpha, int_ior, ext_ior, diffuse_reflectance, nonlinear (0 or 1), ggx (0: Beckmann, 1: GGX), sample_visible
/// (0 or 1).
RoughPlasticBsdf makeRoughPlastic(const float *params) {
    const auto type = params[5] != 0.f ? MicrofacetDistribution::Type::GGX : MicrofacetDistribution::Type::Beckmann;
    return RoughPlasticBsdf(MicrofacetDistribution(type, params[0], params[6] != 0.f), params[1], params[2],
                            Color(params[3], params[3], params[3]), params[4] != 0.f);
}

/// alpha, kd, ks, int_ior, ext_ior (Nori's microfacet, kd and ks given apart).
NoriMicrofacetBsdf makeNoriMicrofacet(const float *params) {
    return NoriMicrofacetBsdf(params[0], params[1], params[2], params[3], params[4]);
}

}  // namespace
}  // namespace mcval

/// Defines the four symbols of NAME from MAKE (params -> a BSDF object) and its parameter names.
#define MCVAL_EXPORT_BSDF(NAME, PARAMS, MAKE)                                                                   \
    MCVAL_DECLARE_BSDF(NAME)                                                                                    \
    const char *bsdf_##NAME##_params = PARAMS;                                                                  \
    void bsdf_##NAME##_eval(const float *params, const float *wi, const float *wo, float *value, size_t n) {   \
        mcval::evalRows(MAKE, params, wi, wo, value, n);                                                        \
    }                                                                                                           \
    void bsdf_##NAME##_pdf(const float *params, const float *wi, const float *wo, float *pdf, size_t n) {       \
        mcval::pdfRows(MAKE, params, wi, wo, pdf, n);                                                           \
    }                                                                                                           \
    void bsdf_##NAME##_sample(const float *params, const float *wi, const float *u, float *wo, float *weight,  \
                              float *pdf, size_t n) {                                                           \
        mcval::sampleRows(MAKE, params, wi, u, wo, weight, pdf, n);                                             \
    }

extern "C" {
MCVAL_EXPORT_BSDF(conductor, "eta,k,specular_reflectance", mcval::makeConductor)
MCVAL_EXPORT_BSDF(dielectric, "int_ior,ext_ior", mcval::makeDielectric)
MCVAL_EXPORT_BSDF(diffuse, "reflectance", mcval::makeDiffuse)
MCVAL_EXPORT_BSDF(microfacet, "alpha,kd,ks,int_ior,ext_ior", mcval::makeNoriMicrofacet)
MCVAL_EXPORT_BSDF(plastic, "int_ior,ext_ior,diffuse_reflectance,nonlinear", mcval::makePlastic)
MCVAL_EXPORT_BSDF(roughconductor, "alpha,eta,k,ggx,sample_visible", mcval::makeRoughConductor)
MCVAL_EXPORT_BSDF(roughdielectric, "alpha,int_ior,ext_ior,ggx,sample_visible", mcval::makeRoughDielectric)
MCVAL_EXPORT_BSDF(roughplastic, "alpha,int_ior,ext_ior,diffuse_reflectance,nonlinear,ggx,sample_visible",
                  mcval::makeRoughPlastic)
}
