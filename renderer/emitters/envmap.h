// Mitsuba's `envmap` emitter: radiance from every direction, read from a latitude-longitude image and
// infinitely far away. Evaluated as Mitsuba 3 evaluates it; sampled in proportion to the image's luminance.
#pragma once

#include <vector>

#include "emitter.h"

namespace mcval {

class EnvmapEmitter final : public Emitter {
public:
    explicit EnvmapEmitter(const EnvironmentMap &map);
    EmitterKind kind() const override { return EmitterKind::Envmap; }
    bool isDelta() const override { return false; }
    /// A direction drawn with density proportional to luminance times sin(theta) over the image's cells.
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override;
    /// The radiance along a ray that escaped in direction at.d: the image interpolated bilinearly.
    Color eval(const EmitterHit &at) const override;
    float pdf(const Vec3f &ref, const EmitterHit &at) const override;

private:
    /// Grid coordinates: x in [0, W] across the image's columns (pixel centres at integers, column W the
    /// copy of column 0), y in [0, H - 1] from the top row (theta = 0) to the bottom one (theta = pi).
    Vec2f gridOf(const Vec3f &local) const;
    Color lookup(const Vec2f &grid) const;
    /// The density by solid angle of a direction in cell (cx, cy) at sin(theta) = sinTheta.
    float cellPdf(int cx, int cy, float sinTheta) const;
    Vec3f toLocal(const Vec3f &d) const;
    Vec3f toWorld(const Vec3f &d) const;

    int m_width, m_height;       ///< the image's; the grid has m_width + 1 columns
    std::vector<float> m_grid;   ///< RGB at the grid's points, times the scale
    Transform m_toWorld;  ///< a rotation
    /// Sampling: the image's W x (H - 1) cells between grid points, each weighed by its corners' mean luminance
    /// times the mean sin(theta) of its two rows (positive wherever the radiance is).
    std::vector<double> m_rowCdf;   ///< cumulative weight of rows 0..r
    std::vector<double> m_cellCdf;  ///< per row, cumulative weight of its cells 0..c
    std::vector<float> m_cellWeight;
    double m_total = 0.0;
};

}  // namespace mcval
