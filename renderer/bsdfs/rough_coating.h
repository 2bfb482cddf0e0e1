// The rough dielectric coating of Mitsuba's `roughplastic`, integrated once per roughness and index: the share of
// light from outside that crosses it at each cos theta, and the share of diffuse light inside that it reflects
// back down. Mitsuba computes both by Gauss-Legendre quadrature over the visible normals' sample space
// (include/mitsuba/render/microfacet.h, eval_transmittance and eval_reflectance); so does this, with the same
// nodes, table and interpolation, so that the two plugins' values agree.
#pragma once

#include <memory>
#include <vector>

#include "microfacet.h"

namespace mcval {

/// Entries of the transmittance table, at cos theta = max(1e-6, i / (size - 1)) (Mitsuba's
/// MI_ROUGH_TRANSMITTANCE_RES).
inline constexpr int kRoughTransmittanceEntries = 64;

struct RoughCoating {
    std::vector<float> externalTransmittance;  ///< kRoughTransmittanceEntries values
    float internalReflectance = 0.f;           ///< cosine-weighted hemispherical average, from inside

    /// The table's value at cos theta in [0, 1], interpolated linearly (Mitsuba's lerp_gather).
    float transmittance(float cosTheta) const;
};

/// The coating of a `type` distribution of roughness alpha over an interface of relative index eta = int / ext,
/// computed at its first request and shared after it (the tables take some 10^6 microfacet samples).
std::shared_ptr<const RoughCoating> roughCoating(MicrofacetDistribution::Type type, float alpha, float eta);

/// The n nodes in (-1, 1) and weights of Gauss-Legendre quadrature, nodes ascending.
void gaussLegendre(int n, std::vector<double> &nodes, std::vector<double> &weights);

}  // namespace mcval
