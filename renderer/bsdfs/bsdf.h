// The BSDF interface, in the local shading frame (z: the shading normal) and Mitsuba 3's convention:
// wi points toward where the light goes (the viewer), wo toward where it comes from (the light); eval
// includes the cosine, f(wi, wo) |cos theta_o|; sample returns the direction, value / pdf and the pdf by
// solid angle.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "../vector.h"

namespace mcval {

using Color = Vec3f;  ///< linear RGB

/// The mean of a colour's channels (Mitsuba's mean() of an RGB texture).
inline float meanOf(const Color &c) { return (c.x + c.y + c.z) / 3.f; }
/// Mitsuba's luminance() of linear sRGB (the Y row of its sRGB to XYZ matrix).
inline float luminance(const Color &c) { return 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z; }

struct BsdfSample {
    Vec3f wo;             ///< the sampled direction, local frame
    Color weight;         ///< eval(wi, wo) / pdf; 0 where nothing is sampled; on a delta lobe, its weight
    float pdf = 0.f;      ///< density of wo by solid angle; infinite on a delta lobe (a mirror's, a glass's)
    /// The relative index of refraction crossed (Mitsuba's bs.eta): the far side's over wi's side where wo
    /// refracts, 1 where it reflects. A path tracer's Russian roulette undoes the radiance it scales by.
    float eta = 1.f;
};

class Bsdf {
public:
    virtual ~Bsdf() = default;
    /// f(wi, wo) |cos theta_o|.
    virtual Color eval(const Vec3f &wi, const Vec3f &wo) const = 0;
    /// The density by solid angle with which sample(wi, .) draws wo.
    virtual float pdf(const Vec3f &wi, const Vec3f &wo) const = 0;
    /// A direction wo drawn with u in [0, 1)^2.
    virtual BsdfSample sample(const Vec3f &wi, const Vec2f &u) const = 0;
    /// As above, with a uniform of its own to choose the lobe (Mitsuba's sample1) where the lobe's probability
    /// depends on the direction drawn, so that u cannot be rescaled for it: the integrators' call. A BSDF that
    /// needs none ignores it.
    virtual BsdfSample sample(const Vec3f &wi, const Vec2f &u, float uLobe) const {
        (void)uLobe;
        return sample(wi, u);
    }
    /// The albedo rho of the side seen from the front (the side the shading normal points to) or from behind,
    /// where that side is Lambertian (eval = rho / pi cos theta_o; a side that reflects nothing is Lambertian
    /// with rho 0); none where it is not. Packet paths (simple, ao) multiply by it instead of calling eval.
    virtual std::optional<Color> lambertianAlbedo(bool front) const = 0;
    /// Whether the back reflects light as a surface of its own (Mitsuba's twosided); otherwise black from behind.
    virtual bool twoSided() const { return false; }
};

/// The scene's BSDFs, which shapes name by index (Mesh::bsdf and the others).
using BsdfList = std::vector<std::shared_ptr<const Bsdf>>;

/// Mitsuba's default BSDF, a shape's without one: diffuse, reflectance 0.5 (one shared instance).
std::shared_ptr<const Bsdf> defaultBsdf();
/// Mitsuba's default BSDF of a shape with an area emitter and no BSDF: diffuse, reflectance 0 (it emits and
/// reflects nothing).
std::shared_ptr<const Bsdf> defaultEmitterBsdf();
/// A list holding only the default BSDF, at index 0.
inline BsdfList defaultBsdfs() { return {defaultBsdf()}; }

}  // namespace mcval
