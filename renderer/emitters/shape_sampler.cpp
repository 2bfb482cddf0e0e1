#include "shape_sampler.h"

#include <algorithm>
#include <cmath>

#include "../frame.h"
#include "../warp.h"

namespace mcval {

namespace {

Vec3f toFloat(const Vec3d &v) { return {float(v.x), float(v.y), float(v.z)}; }
Vec3d toDouble(const Vec3f &v) { return {v.x, v.y, v.z}; }

/// The direction, distance and solid-angle density from ref of point p drawn with density pdfArea.
ShapeSample seenFrom(const Vec3f &ref, const Vec3f &p, const Vec3f &ng, const Vec3f &ns, float pdfArea) {
    ShapeSample s;
    s.p = p;
    s.ng = ng;
    s.ns = ns;
    const Vec3f toP = p - ref;
    s.dist = norm(toP);
    s.d = toP / s.dist;
    s.pdf = areaToSolidAngle(pdfArea, s.dist, s.d, ng);
    return s;
}

/// A triangle mesh, uniform by area: a triangle by its share of the area, then a point on it
/// (Mitsuba's mesh: the triangle's sample value is reused, then square_to_uniform_triangle).
class MeshSampler final : public ShapeSampler {
public:
    explicit MeshSampler(const Mesh &mesh) : m_mesh(mesh) {
        double total = 0.0;
        for (size_t f = 0; f < mesh.indices.size() / 3; ++f) {
            const Vec3f &p0 = corner(f, 0), &p1 = corner(f, 1), &p2 = corner(f, 2);
            total += 0.5 * norm(cross(toDouble(p1 - p0), toDouble(p2 - p0)));
            m_cdf.push_back(total);
        }
        m_area = float(total);
    }
    ShapeSample sample(const Vec3f &ref, const Vec2f &u) const override {
        if (m_cdf.empty() || !(m_area > 0.f)) return {};
        // The triangle whose share of the area holds u.x, and u.x rescaled within it.
        const double target = double(u.x) * m_cdf.back();
        const size_t f = std::min(size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), target) - m_cdf.begin()),
                                  m_cdf.size() - 1);
        const double lo = f == 0 ? 0.0 : m_cdf[f - 1], width = m_cdf[f] - lo;
        const float reused = std::min(float((target - lo) / width), kOneMinusEpsilon);
        // Uniform on the triangle (Mitsuba's square_to_uniform_triangle).
        const float t = detail::safeSqrt(1.f - reused);
        const float b1 = 1.f - t, b2 = t * u.y;
        const Vec3f &p0 = corner(f, 0), &p1 = corner(f, 1), &p2 = corner(f, 2);
        const Vec3f p = p0 + (p1 - p0) * b1 + (p2 - p0) * b2;
        const Vec3f ng = normalize(cross(p1 - p0, p2 - p0));
        Vec3f ns = ng;
        if (!m_mesh.normals.empty()) {
            const uint32_t *tri = &m_mesh.indices[3 * f];
            ns = normalize(m_mesh.normals[tri[0]] * (1.f - b1 - b2) + m_mesh.normals[tri[1]] * b1 +
                           m_mesh.normals[tri[2]] * b2);
        }
        return seenFrom(ref, p, ng, ns, 1.f / m_area);
    }
    float pdf(const Vec3f &, const EmitterHit &at) const override {
        return m_area > 0.f ? areaToSolidAngle(1.f / m_area, at.dist, at.d, at.ng) : 0.f;
    }

private:
    const Vec3f &corner(size_t f, int k) const { return m_mesh.positions[m_mesh.indices[3 * f + k]]; }
    const Mesh &m_mesh;
    std::vector<double> m_cdf;  ///< the area of triangles 0..f
    float m_area = 0.f;
};

/// Mitsuba's sphere: from outside, a direction uniform in the cone the sphere covers (mapped onto its
/// visible cap as Mitsuba does, after akalin.com/sampling-visible-sphere); from inside, uniform by area.
class SphereSampler final : public ShapeSampler {
public:
    explicit SphereSampler(const Sphere &sphere) : m_sphere(sphere) {}
    ShapeSample sample(const Vec3f &ref, const Vec2f &u) const override {
        const Vec3f &c = m_sphere.center;
        const float r = m_sphere.radius;
        const Vec3f dc = c - ref;
        const float dc2 = squaredNorm(dc);
        if (seesCone(dc2)) {
            const float invDc = 1.f / std::sqrt(dc2), sinMax = r * invDc, sinMax2 = sinMax * sinMax,
                        invSinMax = 1.f / sinMax, cosMax = detail::safeSqrt(1.f - sinMax2);
            // A Taylor expansion below 1.5 degrees, where the direct formula cancels.
            const float sinTheta2 = sinMax2 > 0.00068523f ? 1.f - sq((cosMax - 1.f) * u.x + 1.f) : sinMax2 * u.x;
            const float cosTheta = detail::safeSqrt(1.f - sinTheta2);
            const float cosAlpha = sinTheta2 * invSinMax + cosTheta * detail::safeSqrt(1.f - sinTheta2 * sq(invSinMax));
            const float sinAlpha = detail::safeSqrt(1.f - cosAlpha * cosAlpha);
            const float phi = u.y * 2.f * kPi;
            const Vec3f n = Frame(dc * -invDc).toWorld({std::cos(phi) * sinAlpha, std::sin(phi) * sinAlpha, cosAlpha});
            ShapeSample s = seenFrom(ref, c + n * r, front(n), front(n), 0.f);
            s.pdf = s.dist == 0.f ? 0.f : coneDensity(cosMax);
            return s;
        }
        const Vec3f n = squareToUniformSphere(u);
        return seenFrom(ref, c + n * r, front(n), front(n), 1.f / area());
    }
    float pdf(const Vec3f &ref, const EmitterHit &at) const override {
        const float dc2 = squaredNorm(m_sphere.center - ref);
        if (seesCone(dc2)) {
            const float sinAlpha = m_sphere.radius / std::sqrt(dc2);
            return coneDensity(detail::safeSqrt(1.f - sinAlpha * sinAlpha));
        }
        return areaToSolidAngle(1.f / area(), at.dist, at.d, at.ng);
    }

private:
    /// Mitsuba's RayEpsilon (float32): the margin of the inside test.
    static constexpr float kRayEpsilon = 0x1p-24f * 1500.f;
    /// Whether ref, at squared distance dc2 from the centre, is sampled by the cone (else by area). sample() and
    /// pdf() ask this one test: Mitsuba's pdf_direction tests another margin (sin alpha < 1 - 2^-24), so that a
    /// point within 9e-5 r outside a sphere's inside, as float rounding puts its own hits there, gets the
    /// cone's density for a direction drawn by area, and MIS counts light off the inside twice.
    bool seesCone(float dc2) const {
        const float adjusted = m_sphere.radius * (m_sphere.flipNormals ? 1.f + kRayEpsilon : 1.f - kRayEpsilon);
        return dc2 > adjusted * adjusted;
    }
    static float sq(float x) { return x * x; }
    /// square_to_uniform_cone_pdf: 1 / (2 pi (1 - cos theta_max)).
    static float coneDensity(float cosMax) { return kInv2Pi / (1.f - cosMax); }
    float area() const { return 4.f * kPi * m_sphere.radius * m_sphere.radius; }
    Vec3f front(const Vec3f &outward) const { return m_sphere.flipNormals ? -outward : outward; }
    const Sphere &m_sphere;
};

/// Mitsuba's disk: uniform by area (our uniform-disk warp; Mitsuba's concentric map has the same density).
class DiskSampler final : public ShapeSampler {
public:
    explicit DiskSampler(const Disk &disk) : m_disk(disk) {
        const Vec3d m = disk.toWorld.normal({0.0, 0.0, disk.flipNormals ? -1.0 : 1.0});
        m_normal = toFloat(m * (1.0 / norm(m)));
        // A linear map takes the unit disk (area pi) to an ellipse of pi |c0 x c1|.
        m_invArea = float(1.0 / (double(kPi) * norm(cross(disk.toWorld.column(0), disk.toWorld.column(1)))));
    }
    ShapeSample sample(const Vec3f &ref, const Vec2f &u) const override {
        const Vec2f q = squareToUniformDisk(u);
        const Vec3f p = toFloat(m_disk.toWorld.point({q.x, q.y, 0.0}));
        return seenFrom(ref, p, m_normal, m_normal, m_invArea);
    }
    float pdf(const Vec3f &, const EmitterHit &at) const override {
        return areaToSolidAngle(m_invArea, at.dist, at.d, at.ng);
    }

private:
    const Disk &m_disk;
    Vec3f m_normal;
    float m_invArea;
};

/// Mitsuba's cylinder, uniform by area: phi and z uniform, weighted by the exact area element of to_world
/// (for a to_world that keeps the circle round, as Mitsuba's, that is uniform by area; otherwise still a
/// density, by the area element of the affine map).
class CylinderSampler final : public ShapeSampler {
public:
    explicit CylinderSampler(const Cylinder &cylinder) : m_cylinder(cylinder) {}
    ShapeSample sample(const Vec3f &ref, const Vec2f &u) const override {
        const double phi = 2.0 * double(kPi) * u.y;
        const Vec3f p = toFloat(m_cylinder.toWorld.point({std::cos(phi), std::sin(phi), u.x}));
        return seenFrom(ref, p, normalAt(phi), normalAt(phi), densityByArea(phi));
    }
    float pdf(const Vec3f &, const EmitterHit &at) const override {
        const Vec3d local = m_cylinder.toWorld.inversePoint(toDouble(at.p));
        return areaToSolidAngle(densityByArea(std::atan2(local.y, local.x)), at.dist, at.d, at.ng);
    }

private:
    /// Uniform (phi, z) over [0, 2 pi) x [0, 1] has density 1 / (2 pi); by area, divided by the area element
    /// |dp/dphi x dp/dz|.
    float densityByArea(double phi) const {
        const Affine &m = m_cylinder.toWorld;
        const Vec3d dPhi = m.column(0) * -std::sin(phi) + m.column(1) * std::cos(phi);
        return float(1.0 / (2.0 * double(kPi) * norm(cross(dPhi, m.column(2)))));
    }
    Vec3f normalAt(double phi) const {
        const double sign = m_cylinder.flipNormals ? -1.0 : 1.0;
        const Vec3d m = m_cylinder.toWorld.normal({sign * std::cos(phi), sign * std::sin(phi), 0.0});
        return toFloat(m * (1.0 / norm(m)));
    }
    const Cylinder &m_cylinder;
};

}  // namespace

std::unique_ptr<ShapeSampler> makeShapeSampler(const Mesh &mesh) { return std::make_unique<MeshSampler>(mesh); }
std::unique_ptr<ShapeSampler> makeShapeSampler(const Sphere &sphere) { return std::make_unique<SphereSampler>(sphere); }
std::unique_ptr<ShapeSampler> makeShapeSampler(const Disk &disk) { return std::make_unique<DiskSampler>(disk); }
std::unique_ptr<ShapeSampler> makeShapeSampler(const Cylinder &cylinder) {
    return std::make_unique<CylinderSampler>(cylinder);
}

}  // namespace mcval
