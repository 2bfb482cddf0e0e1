// Mitsuba 3's isotropic microfacet distribution (include/mitsuba/render/microfacet.h): Beckmann or GGX of
// roughness alpha, its normals sampled from D(m) cos theta_m or, with sampleVisible, from the normals visible
// from wi (Heitz and d'Eon 2014). Local frame, z the macro-surface normal.
#pragma once

#include "../vector.h"

namespace mcval {

struct MicrofacetSample {
    Vec3f m;          ///< the sampled microfacet normal
    float pdf = 0.f;  ///< its density by solid angle (MicrofacetDistribution::pdf)
};

class MicrofacetDistribution {
public:
    enum class Type { Beckmann, GGX };

    MicrofacetDistribution(Type type, float alpha, bool sampleVisible)
        : m_type(type), m_alpha(alpha), m_sampleVisible(sampleVisible) {}

    /// D(m), the density of microfacet normals by projected area (0 below the surface, and where D cos < 1e-20).
    float eval(const Vec3f &m) const;
    /// The density with which sample(wi, .) draws m: D(m) cos theta_m, or the visible normals' density.
    float pdf(const Vec3f &wi, const Vec3f &m) const;
    /// Smith's masking of direction v by the microfacets of normal m (0 where v sees m's back).
    float smithG1(const Vec3f &v, const Vec3f &m) const;
    /// Smith's separable shadowing-masking of wi and wo.
    float G(const Vec3f &wi, const Vec3f &wo, const Vec3f &m) const { return smithG1(wi, m) * smithG1(wo, m); }
    MicrofacetSample sample(const Vec3f &wi, float u1, float u2) const;

    Type type() const { return m_type; }
    float alpha() const { return m_alpha; }
    bool sampleVisible() const { return m_sampleVisible; }

private:
    /// A slope of the visible normals of the unit-roughness distribution seen at cos theta_i.
    void sampleVisible11(float cosThetaI, float u1, float u2, float &slopeX, float &slopeY) const;

    Type m_type;
    float m_alpha;
    bool m_sampleVisible;
};

}  // namespace mcval
