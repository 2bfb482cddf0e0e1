// Mitsuba's rough-coating integrals (eval_transmittance, eval_reflectance in include/mitsuba/render/microfacet.h
// and their use in src/bsdfs/roughplastic.cpp).
#include "rough_coating.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "dielectric.h"

namespace mcval {

void gaussLegendre(int n, std::vector<double> &nodes, std::vector<double> &weights) {
    nodes.assign(n, 0.0);
    weights.assign(n, 0.0);
    for (int i = 0; i < (n + 1) / 2; ++i) {
        // Newton's method on P_n from Tricomi's estimate of the i-th largest root.
        double x = std::cos(M_PI * (i + 0.75) / (n + 0.5)), derivative = 0.0;
        for (int iteration = 0; iteration < 100; ++iteration) {
            double p0 = 1.0, p1 = x;  // P_{k-1}, P_k by the three-term recurrence
            for (int k = 1; k < n; ++k) {
                const double p2 = ((2.0 * k + 1.0) * x * p1 - k * p0) / (k + 1.0);
                p0 = p1, p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            const double step = p1 / derivative;
            x -= step;
            if (std::abs(step) < 1e-15) break;
        }
        const double w = 2.0 / ((1.0 - x * x) * derivative * derivative);
        nodes[i] = -x, nodes[n - 1 - i] = x;
        weights[i] = weights[n - 1 - i] = w;
    }
}

namespace {

/// Mitsuba's resolution of the quadrature: finer where the interface can reflect totally (eta < 1).
int resolution(float eta) { return eta > 1.f ? 32 : 128; }

/// The integral over the unit square of `integrand(m, wi)`, m the visible normal drawn from wi with the square's
/// point, by resolution(eta)^2 Gauss-Legendre nodes.
template <typename Integrand>
float overVisibleNormals(const MicrofacetDistribution &distribution, const Vec3f &wi, float eta,
                         Integrand integrand) {
    std::vector<double> nodes, weights;
    gaussLegendre(resolution(eta), nodes, weights);
    float sum = 0.f;
    for (size_t a = 0; a < nodes.size(); ++a)
        for (size_t b = 0; b < nodes.size(); ++b) {
            const float u1 = static_cast<float>(nodes[b] * 0.5 + 0.5), u2 = static_cast<float>(nodes[a] * 0.5 + 0.5);
            const Vec3f m = distribution.sample(wi, u1, u2).m;
            sum += integrand(m) * static_cast<float>(weights[a] * weights[b]) * 0.25f;
        }
    return sum;
}

/// Smith's masking as Mitsuba computes it, by Walter et al.'s rational approximation for Beckmann: the coating's
/// tables define the model (no density has to integrate to 1 there), so they take Mitsuba's term.
float mitsubaSmithG1(const MicrofacetDistribution &distribution, const Vec3f &v, const Vec3f &m) {
    if (distribution.type() != MicrofacetDistribution::Type::Beckmann) return distribution.smithG1(v, m);
    if (dot(v, m) * v.z <= 0.f) return 0.f;
    const float xyAlpha2 = distribution.alpha() * distribution.alpha() * (v.x * v.x + v.y * v.y);
    if (xyAlpha2 == 0.f) return 1.f;
    const float a = 1.f / std::sqrt(xyAlpha2 / (v.z * v.z)), a2 = a * a;
    return a >= 1.6f ? 1.f : (3.535f * a + 2.181f * a2) / (1.f + 2.276f * a + 2.577f * a2);
}

/// The share of light arriving along wi (above) that the rough interface transmits, its masking included.
float transmittance(const MicrofacetDistribution &distribution, const Vec3f &wi, float eta) {
    return overVisibleNormals(distribution, wi, eta, [&](const Vec3f &m) {
        const Fresnel f = fresnelDielectric(dot(wi, m), eta);
        const Vec3f wo = m * (dot(wi, m) * f.etaTi + f.cosThetaT) - wi * f.etaTi;
        return wo.z * wi.z >= 0.f ? 0.f : mitsubaSmithG1(distribution, wo, m) * (1.f - f.reflectance);
    });
}

/// The share it reflects, seen through an interface of relative index eta.
float reflectance(const MicrofacetDistribution &distribution, const Vec3f &wi, float eta) {
    return overVisibleNormals(distribution, wi, eta, [&](const Vec3f &m) {
        const Vec3f wo = m * (2.f * dot(wi, m)) - wi;
        if (wo.z <= 0.f || wi.z <= 0.f) return 0.f;
        return mitsubaSmithG1(distribution, wo, m) * fresnelDielectric(dot(wi, m), eta).reflectance;
    });
}

std::shared_ptr<const RoughCoating> computeCoating(MicrofacetDistribution::Type type, float alpha, float eta) {
    // Mitsuba integrates over visible normals whatever the BSDF samples from.
    const MicrofacetDistribution distribution(type, alpha, true);
    auto coating = std::make_shared<RoughCoating>();
    float internal = 0.f;
    for (int i = 0; i < kRoughTransmittanceEntries; ++i) {
        const float mu = std::max(1e-6f, static_cast<float>(i) / (kRoughTransmittanceEntries - 1));
        const Vec3f wi(std::sqrt(1.f - mu * mu), 0.f, mu);
        coating->externalTransmittance.push_back(transmittance(distribution, wi, eta));
        internal += reflectance(distribution, wi, 1.f / eta) * mu;
    }
    // Mitsuba's average over the table's cosines, times 2: the cosine-weighted hemisphere's mean.
    coating->internalReflectance = 2.f * internal / kRoughTransmittanceEntries;
    return coating;
}

}  // namespace

float RoughCoating::transmittance(float cosTheta) const {
    const float x = cosTheta * (kRoughTransmittanceEntries - 1);
    const int index = std::clamp(static_cast<int>(x), 0, kRoughTransmittanceEntries - 2);
    const float w1 = x - static_cast<float>(index);
    return (1.f - w1) * externalTransmittance[index] + w1 * externalTransmittance[index + 1];
}

std::shared_ptr<const RoughCoating> roughCoating(MicrofacetDistribution::Type type, float alpha, float eta) {
    if (!(std::isfinite(alpha) && std::isfinite(eta))) return computeCoating(type, alpha, eta);  // no map key
    static std::mutex mutex;
    static std::map<std::tuple<int, float, float>, std::shared_ptr<const RoughCoating>> cache;
    const auto key = std::make_tuple(static_cast<int>(type), alpha, eta);
    std::lock_guard<std::mutex> lock(mutex);
    auto &coating = cache[key];
    if (!coating) coating = computeCoating(type, alpha, eta);
    return coating;
}

}  // namespace mcval
