// The emitter models: each sample's pdf is pdf() at the surface its ray reaches and its weight is eval / pdf
// (the sampler and its density agree); the irradiance a Monte Carlo estimate draws from a disk, a rectangle,
// a sphere and the environment is the closed form; delta lights report delta; and the wrong twins (a pdf
// left in area measure, without distance^2 / cos) fail the same checks.
#include <array>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "embree_scene.h"
#include "emitters/area.h"
#include "emitters/delta_lights.h"
#include "emitters/scene_emitters.h"
#include "emitters/shape_sampler.h"
#include "mesh.h"
#include "warp.h"

using namespace mcval;

namespace {

/// Uniforms in [0, 1), fixed by the seed.
struct Uniforms {
    std::mt19937 rng;
    explicit Uniforms(uint32_t seed) : rng(seed) {}
    float next() { return float(rng() >> 8) * 0x1p-24f; }
    Vec2f next2D() { return {next(), next()}; }
};

bool close(float a, float b, float rel) { return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-12f; }

/// A scene of the given shapes, each emitting radiance L, and the models of its emitters.
struct EmittingScene {
    SceneDescription scene;
    std::unique_ptr<EmbreeScene> embree;
    std::unique_ptr<SceneEmitters> emitters;
    void build() {
        embree = std::make_unique<EmbreeScene>(scene.meshes, scene.spheres, scene.disks, scene.cylinders);
        emitters = std::make_unique<SceneEmitters>(scene);
    }
};

const Color kL{2.f, 3.f, 4.f};

/// A disk of radius r at height h over the origin, facing down.
Disk downwardDisk(float r, float h) {
    Disk disk;
    disk.toWorld = Affine::from(Transform::translate({0.f, 0.f, h}) * Transform::scale({r, r, 1.f}));
    disk.flipNormals = true;
    disk.areaRadiance = kL;
    return disk;
}

/// A 2a x 2b rectangle at height h over the origin, facing down.
Mesh downwardRectangle(float a, float b, float h) {
    Mesh mesh = makeRectangle(Transform::translate({0.f, 0.f, h}) * Transform::rotate({1.f, 0.f, 0.f}, 180.f) *
                              Transform::scale({a, b, 1.f}));
    mesh.areaRadiance = kL;
    return mesh;
}

/// The samples from ref whose ray, traced, does not reach the surface sampled (its emitter, its point), or
/// whose pdf is not pdf() there, or whose weight is not eval / pdf there. Samples with pdf 0 must weigh 0.
int sampleMismatches(const Emitter &emitter, int index, const EmbreeScene &embree, const Vec3f &ref, int n,
                     uint32_t seed) {
    Uniforms u(seed);
    int bad = 0, used = 0;
    for (int k = 0; k < n; ++k) {
        const EmitterSample s = emitter.sample(ref, u.next2D());
        if (!(s.pdf > 0.f)) {
            bad += s.weight.x != 0.f;
            continue;
        }
        // At grazing angles the pdf's 1 / cos amplifies the rounding of the point: compare elsewhere.
        if (std::abs(dot(s.d, s.n)) < 1e-2f) continue;
        ++used;
        Ray ray;
        ray.o = ref;
        ray.d = s.d;
        Hit hit;
        if (!embree.intersect(ray, hit) || hit.emitter != index || !close(hit.t, s.dist, 1e-3f)) {
            ++bad;
            continue;
        }
        const EmitterHit at = emitterHit(hit, s.d);
        const float pdf = emitter.pdf(ref, at);
        const Color value = emitter.eval(at);
        bad += !close(pdf, s.pdf, 2e-3f) || !close(value.x / s.pdf, s.weight.x, 2e-3f) ||
               !close(value.z / s.pdf, s.weight.z, 2e-3f);
    }
    return used == 0 ? n : bad;
}

/// The Monte Carlo estimate of the irradiance at ref on a surface of normal nr (red channel), unshadowed.
double irradiance(const Emitter &emitter, const Vec3f &ref, const Vec3f &nr, int n, uint32_t seed) {
    Uniforms u(seed);
    double sum = 0.0;
    for (int k = 0; k < n; ++k) {
        const EmitterSample s = emitter.sample(ref, u.next2D());
        sum += double(s.weight.x) * std::max(0.f, dot(s.d, nr));
    }
    return sum / n;
}

/// E = 2 L (X atan Y' + Y atan X') for a 2a x 2b rectangle at height h, parallel, centred over the point
/// (four times the corner form factor of a rectangle, times pi L).
double rectangleIrradiance(double L, double a, double b, double h) {
    const double x = a / h, y = b / h;
    return 2.0 * L *
           (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
            y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)));
}

/// An area emitter whose densities are left in area measure (no distance^2 / cos): the sample's pdf and
/// weight consistently so (`alsoSample`), or only pdf().
class AreaMeasureTwin final : public Emitter {
public:
    AreaMeasureTwin(const Emitter &right, bool alsoSample) : m_right(right), m_alsoSample(alsoSample) {}
    EmitterKind kind() const override { return EmitterKind::Area; }
    bool isDelta() const override { return false; }
    EmitterSample sample(const Vec3f &ref, const Vec2f &u) const override {
        EmitterSample s = m_right.sample(ref, u);
        if (m_alsoSample && s.pdf > 0.f) {
            const float pdfArea = s.pdf * std::abs(dot(s.d, s.n)) / (s.dist * s.dist);
            s.weight = s.weight * (s.pdf / pdfArea);
            s.pdf = pdfArea;
        }
        return s;
    }
    Color eval(const EmitterHit &at) const override { return m_right.eval(at); }
    float pdf(const Vec3f &ref, const EmitterHit &at) const override {
        return m_right.pdf(ref, at) * std::abs(dot(at.d, at.ng)) / (at.dist * at.dist);
    }

private:
    const Emitter &m_right;
    bool m_alsoSample;
};

}  // namespace

TEST(Emitters, AreaSamplesMatchTheirPdfAndEvalOnEveryShape) {
    EmittingScene s;
    s.scene.meshes.push_back(downwardRectangle(1.f, 0.5f, 2.f));
    Mesh cube = makeCube(Transform::translate({4.f, 0.f, 1.f}) * Transform::scale({0.5f, 0.7f, 0.3f}));
    cube.areaRadiance = kL;
    s.scene.meshes.push_back(cube);
    Sphere sphere;
    sphere.center = {-4.f, 1.f, 2.f};
    sphere.radius = 0.8f;
    sphere.areaRadiance = kL;
    s.scene.spheres.push_back(sphere);
    s.scene.disks.push_back(downwardDisk(0.7f, 3.f));
    s.scene.disks.back().flipNormals = false;  // rotated to face down
    s.scene.disks.back().toWorld = Affine::from(Transform::translate({0.f, 4.f, 3.f}) *
                                                Transform::rotate({1.f, 1.f, 0.f}, 150.f) *
                                                Transform::scale({0.7f, 0.4f, 1.f}));
    Cylinder cylinder;
    cylinder.toWorld = Affine::from(Transform::translate({0.f, -4.f, 1.f}) * Transform::scale({0.5f, 0.5f, 2.f}));
    cylinder.areaRadiance = kL;
    s.scene.cylinders.push_back(cylinder);
    s.build();
    ASSERT_EQ(s.emitters->size(), 5u);
    const Vec3f ref{0.1f, -0.2f, 0.f};
    for (size_t i = 0; i < s.emitters->size(); ++i) {
        EXPECT_EQ((*s.emitters)[i].kind(), EmitterKind::Area);
        EXPECT_FALSE((*s.emitters)[i].isDelta());
        EXPECT_EQ(sampleMismatches((*s.emitters)[i], int(i), *s.embree, ref, 2000, 7 + i), 0) << "emitter " << i;
    }
}

TEST(Emitters, ASphereSeenFromInsideIsSampledByArea) {
    EmittingScene s;
    Sphere sphere;
    sphere.center = {0.f, 0.f, 0.f};
    sphere.radius = 2.f;
    sphere.flipNormals = true;  // emitting inward
    sphere.areaRadiance = kL;
    s.scene.spheres.push_back(sphere);
    s.build();
    EXPECT_EQ(sampleMismatches((*s.emitters)[0], 0, *s.embree, {0.3f, 0.5f, -0.4f}, 2000, 3), 0);
    // Inside a sphere of radiance L every direction sees L: E = pi L.
    EXPECT_NEAR(irradiance((*s.emitters)[0], {0.3f, 0.5f, -0.4f}, {0.f, 0.f, 1.f}, 200000, 4), kPi * kL.x,
                0.01 * kPi * kL.x);
}

TEST(Emitters, ASphereGivesAPointOnItsOwnSurfaceTheDensityItSampledWith) {
    // A furnace's wall far from the origin: float rounding puts its own hits up to a few 1e-6 off the sphere,
    // inside or out. The density pdf() gives each sampled direction must be the one it was drawn with,
    // or MIS weights do not sum to 1 (Mitsuba's pdf_direction tests another margin than its sample_direction).
    for (const bool flip : {true, false}) {
        Sphere sphere;
        sphere.center = {10.f, -20.f, 30.f};
        sphere.radius = 1.f;
        sphere.flipNormals = flip;
        const auto sampler = makeShapeSampler(sphere);
        Uniforms u(11);
        int bad = 0;
        for (int k = 0; k < 4000; ++k) {
            const Vec3f n = squareToUniformSphere(u.next2D());
            const float off = std::array<float, 5>{0.f, 1e-6f, 1e-5f, 5e-5f, -1e-5f}[k % 5];
            const Vec3f ref = sphere.center + n * (sphere.radius * (1.f + off));
            const ShapeSample s = sampler->sample(ref, u.next2D());
            if (!(s.pdf > 0.f)) continue;
            EmitterHit at;
            at.p = s.p;
            at.ng = s.ng;
            at.ns = s.ns;
            at.d = s.d;
            at.dist = s.dist;
            bad += !close(sampler->pdf(ref, at), s.pdf, 1e-4f);
        }
        EXPECT_EQ(bad, 0) << (flip ? "inside" : "outside");
    }
}

TEST(Emitters, TheSideAMeshsNormalsFaceEmitsWhateverItsWinding) {
    // Nori's furnace box is wound outwards with its vertex normals inwards: the inside emits (eval reads the
    // shading normal, as Mitsuba's), so light samples must find it there, with the density pdf() gives the hits.
    EmittingScene s;
    Mesh woundUp = makeRectangle(Transform::translate({0.f, 0.f, 2.f}) * Transform::scale({1.f, 0.5f, 1.f}));
    woundUp.normals.assign(woundUp.positions.size(), Vec3f{0.f, 0.f, -1.f});
    woundUp.areaRadiance = kL;
    s.scene.meshes.push_back(woundUp);
    s.build();
    const Vec3f below{0.1f, -0.2f, 0.f}, above{0.1f, -0.2f, 4.f};
    EXPECT_EQ(sampleMismatches((*s.emitters)[0], 0, *s.embree, below, 2000, 5), 0);
    // The irradiance below is the rectangle's closed form; above, the back, nothing arrives.
    EXPECT_NEAR(irradiance((*s.emitters)[0], {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}, 200000, 6),
                rectangleIrradiance(kL.x, 1.0, 0.5, 2.0), 0.01 * rectangleIrradiance(kL.x, 1.0, 0.5, 2.0));
    EXPECT_EQ(irradiance((*s.emitters)[0], above, {0.f, 0.f, -1.f}, 1000, 7), 0.0);
}

TEST(Emitters, HitsNameTheirEmitterInGeometryOrder) {
    EmittingScene s;
    s.scene.meshes.push_back(makeRectangle(Transform::translate({0.f, 0.f, -5.f})));  // does not emit
    s.scene.meshes.push_back(downwardRectangle(1.f, 1.f, 2.f));
    s.scene.disks.push_back(downwardDisk(1.f, 2.f));
    s.scene.disks.back().toWorld = Affine::from(Transform::translate({5.f, 0.f, 2.f}));
    s.scene.pointLights.push_back({{0.f, 0.f, 9.f}, {1.f, 1.f, 1.f}});
    s.scene.environment = Color(1.f, 1.f, 1.f);
    s.build();
    ASSERT_EQ(s.emitters->size(), 4u);
    EXPECT_EQ(s.emitters->environment(), 3);
    EXPECT_EQ((*s.emitters)[2].kind(), EmitterKind::Point);
    Hit hit;
    Ray up;
    up.o = {0.f, 0.f, 0.f};
    up.d = {0.f, 0.f, 1.f};
    ASSERT_TRUE(s.embree->intersect(up, hit));
    EXPECT_EQ(hit.emitter, 0);
    up.o = {5.f, 0.f, 0.f};
    ASSERT_TRUE(s.embree->intersect(up, hit));
    EXPECT_EQ(hit.emitter, 1);
    Ray down;
    down.o = {0.f, 0.f, 0.f};
    down.d = {0.f, 0.f, -1.f};
    ASSERT_TRUE(s.embree->intersect(down, hit));
    EXPECT_EQ(hit.emitter, -1);
    // A packet of camera rays names them too, lane by lane, and so does a packet built by hand.
    RayHitPacket rays;
    HitPacket hits;
    rays.set(0, true, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}, 0.f, 1e30f);
    rays.set(1, true, {5.f, 0.f, 0.f}, {0.f, 0.f, 1.f}, 0.f, 1e30f);
    rays.set(2, true, {0.f, 0.f, 0.f}, {0.f, 0.f, -1.f}, 0.f, 1e30f);
    rays.set(3, true, {0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, 0.f, 1e30f);  // escapes
    s.embree->intersect(rays, 4, hits);
    EXPECT_EQ(hits.hit(0).emitter, 0);
    EXPECT_EQ(hits.hit(1).emitter, 1);
    EXPECT_EQ(hits.hit(2).emitter, -1);
    EXPECT_EQ(hits.hit(3).emitter, -1);
    HitPacket byHand;
    byHand.clearHit(0);
    byHand.setHit(0, hits.hit(1));
    EXPECT_EQ(byHand.hit(0).emitter, 1);
}

TEST(Emitters, TheIrradianceOfADiskARectangleAndASphereIsTheClosedForm) {
    const Vec3f ref{0.f, 0.f, 0.f}, up{0.f, 0.f, 1.f};
    // A disk of angular radius alpha on the axis: E = pi L sin^2 alpha.
    {
        EmittingScene s;
        s.scene.disks.push_back(downwardDisk(1.5f, 2.f));
        s.build();
        const double sin2 = 1.5 * 1.5 / (1.5 * 1.5 + 2.0 * 2.0);
        EXPECT_NEAR(irradiance((*s.emitters)[0], ref, up, 200000, 11), kPi * kL.x * sin2, 0.005 * kPi * kL.x * sin2);
    }
    {
        EmittingScene s;
        s.scene.meshes.push_back(downwardRectangle(1.f, 0.6f, 1.3f));
        s.build();
        const double expected = rectangleIrradiance(kL.x, 1.0, 0.6, 1.3);
        EXPECT_NEAR(irradiance((*s.emitters)[0], ref, up, 200000, 12), expected, 0.005 * expected);
    }
    // A sphere of radius r at distance D overhead: E = pi L (r / D)^2.
    {
        EmittingScene s;
        Sphere sphere;
        sphere.center = {0.f, 0.f, 3.f};
        sphere.radius = 1.f;
        sphere.areaRadiance = kL;
        s.scene.spheres.push_back(sphere);
        s.build();
        const double expected = kPi * kL.x / 9.0;
        EXPECT_NEAR(irradiance((*s.emitters)[0], ref, up, 200000, 13), expected, 0.005 * expected);
    }
    // The environment over a plane: E = pi L.
    {
        EmittingScene s;
        s.scene.meshes.push_back(makeRectangle(Transform::translate({0.f, 0.f, -5.f})));
        s.scene.environment = kL;
        s.build();
        EXPECT_NEAR(irradiance((*s.emitters)[0], ref, up, 400000, 14), kPi * kL.x, 0.01 * kPi * kL.x);
    }
}

TEST(Emitters, APdfLeftInAreaMeasureFailsTheSameChecks) {
    EmittingScene s;
    s.scene.disks.push_back(downwardDisk(1.5f, 2.f));
    s.build();
    const Emitter &right = (*s.emitters)[0];
    const double sin2 = 1.5 * 1.5 / (1.5 * 1.5 + 2.0 * 2.0), expected = kPi * kL.x * sin2;
    // pdf() in area measure, sample() right: the sample's pdf is not pdf() where its ray lands.
    const AreaMeasureTwin pdfOnly(right, false);
    EXPECT_GT(sampleMismatches(pdfOnly, 0, *s.embree, {0.f, 0.f, 0.f}, 2000, 5), 1000);
    // Both in area measure, consistently: the sampler and its density agree, the irradiance does not.
    const AreaMeasureTwin both(right, true);
    EXPECT_EQ(sampleMismatches(both, 0, *s.embree, {0.f, 0.f, 0.f}, 2000, 5), 0);
    EXPECT_GT(std::abs(irradiance(both, {0.f, 0.f, 0.f}, {0.f, 0.f, 1.f}, 200000, 11) - expected), 0.1 * expected);
}

TEST(Emitters, OnlyTheFrontEmits) {
    EmittingScene s;
    s.scene.disks.push_back(downwardDisk(1.f, 2.f));
    s.build();
    const Emitter &disk = (*s.emitters)[0];
    // From above, the disk shows its back: nothing arrives, and a ray that meets it there has pdf 0.
    Uniforms u(9);
    for (int k = 0; k < 100; ++k) {
        const EmitterSample back = disk.sample({0.f, 0.f, 5.f}, u.next2D());
        EXPECT_EQ(back.pdf, 0.f);
        EXPECT_EQ(back.weight.x, 0.f);
    }
    Ray ray;
    ray.o = {0.2f, 0.f, 5.f};
    ray.d = {0.f, 0.f, -1.f};
    Hit hit;
    ASSERT_TRUE(s.embree->intersect(ray, hit));
    EXPECT_EQ(disk.eval(emitterHit(hit, ray.d)).x, 0.f);
    EXPECT_EQ(disk.pdf(ray.o, emitterHit(hit, ray.d)), 0.f);
}

TEST(Emitters, DeltaLightsReportDeltaAndMitsubasWeights) {
    const PointEmitter point({{0.f, 0.f, 2.f}, {8.f, 8.f, 8.f}});
    const EmitterSample p = point.sample({0.f, 0.f, 0.f}, {0.3f, 0.6f});
    EXPECT_TRUE(point.isDelta());
    EXPECT_TRUE(p.delta);
    EXPECT_EQ(p.pdf, 1.f);
    EXPECT_FLOAT_EQ(p.weight.x, 2.f);  // I / r^2
    EXPECT_FLOAT_EQ(p.d.z, 1.f);
    EXPECT_FLOAT_EQ(p.dist, 2.f);
    EXPECT_EQ(point.pdf({0.f, 0.f, 0.f}, escaped({0.f, 0.f, 1.f})), 0.f);
    EXPECT_EQ(point.eval(escaped({0.f, 0.f, 1.f})).x, 0.f);

    // A spot at the origin shining down -z... by to_world: rotated 180 degrees about x.
    SpotLight light;
    light.toWorld = Transform::rotate({1.f, 0.f, 0.f}, 180.f);
    light.intensity = {4.f, 4.f, 4.f};
    light.cutoffAngle = 20.f;
    light.beamWidth = 15.f;
    const SpotEmitter spot(light);
    EXPECT_TRUE(spot.isDelta());
    const auto at = [&](float degrees) {
        const float a = degrees * kPi / 180.f;
        return spot.sample({std::sin(a), 0.f, -std::cos(a)}, {0.5f, 0.5f});  // at distance 1
    };
    EXPECT_TRUE(at(0.f).delta);
    EXPECT_FLOAT_EQ(at(0.f).weight.x, 4.f);
    EXPECT_FLOAT_EQ(at(14.f).weight.x, 4.f);
    EXPECT_NEAR(at(17.5f).weight.x, 2.f, 1e-3f);  // halfway from beam_width to cutoff_angle, linear in angle
    EXPECT_EQ(at(21.f).weight.x, 0.f);
    EXPECT_EQ(at(170.f).weight.x, 0.f);

    const DirectionalEmitter sun({{0.f, 0.f, -2.f}, {3.f, 3.f, 3.f}});
    const EmitterSample d = sun.sample({1.f, 2.f, 3.f}, {0.1f, 0.9f});
    EXPECT_TRUE(sun.isDelta());
    EXPECT_TRUE(d.delta);
    EXPECT_FLOAT_EQ(d.d.z, 1.f);  // toward the light: against its direction
    EXPECT_FLOAT_EQ(d.weight.x, 3.f);
    EXPECT_TRUE(std::isinf(d.dist));
}

TEST(Emitters, TheEmitterSamplerIsUniformAndReusesItsSample) {
    const EmitterSampler none(0);
    EXPECT_EQ(none.sample(0.5f).index, -1);
    const EmitterSampler four(4);
    EXPECT_FLOAT_EQ(four.pmf(2), 0.25f);
    EXPECT_EQ(four.pmf(4), 0.f);
    EXPECT_EQ(four.pmf(-1), 0.f);
    const EmitterSampler::Choice c = four.sample(0.6f);
    EXPECT_EQ(c.index, 2);
    EXPECT_FLOAT_EQ(c.pmf, 0.25f);
    EXPECT_NEAR(c.reused, 0.4f, 1e-6f);
    EXPECT_EQ(four.sample(kOneMinusEpsilon).index, 3);
    EXPECT_LT(four.sample(kOneMinusEpsilon).reused, 1.f);
    EXPECT_EQ(four.sample(0.f).index, 0);
}
