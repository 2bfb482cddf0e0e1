#include "embree_scene.h"


#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "cylinder.h"
#include "disk.h"
#include "error.h"
#include "sphere.h"
#include "user_geometry.h"

namespace mcval {

namespace {
// Embree calls this from C code, where an exception must not pass: keep the message, throw later.
thread_local std::string tLastError;
void onEmbreeError(void *, RTCError code, const char *message) {
    tLastError = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

/// The spawn-ray offset floor per unit of a shape's size, 64 float epsilons: far above the rounding
/// of a hit point, yet small enough that no shadow ray clears a neighbouring facet it should graze.
/// Visibility at a point is the limit of a vanishing offset; Mitsuba's larger one (1500 epsilons of
/// 1 + max|p|) lets up to 2.6x the light through at the terminator of smooth-shaded fine meshes
/// (highpoly, simple), so the reference renders with this limit too (harness mcval_direct).
constexpr float kOffsetFloorPerSize = 64.f * 0x1p-24f;

/// Half the largest side of the box around the points: a shape's size. Zero if it has no extent (a
/// degenerate shape that no ray hits), which then does not set the offset floor.
float halfExtent(const std::vector<Vec3f> &points) {
    Vec3f lo = points.empty() ? Vec3f() : points[0], hi = lo;
    for (const Vec3f &p : points) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    return 0.5f * std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
}

}  // namespace

EmbreeScene::EmbreeScene(const std::vector<Mesh> &meshes, const std::vector<Sphere> &spheres,
                         const std::vector<Disk> &disks, const std::vector<Cylinder> &cylinders, const BsdfList &bsdfs)
    : m_meshes(meshes), m_spheres(spheres), m_disks(disks), m_cylinders(cylinders) {
    m_device = rtcNewDevice(nullptr);
    if (!m_device) throw std::runtime_error("cannot create an Embree device");
    rtcSetDeviceErrorFunction(m_device, onEmbreeError, nullptr);
    m_scene = rtcNewScene(m_device);
    // Robust mode closes the cracks between neighbouring triangles that rays otherwise slip through
    // (a rectangle's diagonal would read 0.4995 instead of 0.5 under AO).
    rtcSetSceneFlags(m_scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(m_scene, RTC_BUILD_QUALITY_HIGH);  // a slower build for faster traversal
    // The offset floor scales with the scene's smallest shape, so a large floor does not inflate it
    // (its rays would clear contact shadows). Scaling the scene scales the floor: the image does not change.
    float smallest = std::numeric_limits<float>::infinity();
    size_t triangles = 0, smooth = 0;
    for (const Mesh &mesh : meshes) {
        triangles += mesh.indices.size() / 3;
        smooth += mesh.normals.empty() ? 0 : mesh.indices.size() / 3;
    }
    // The tables are indexed with 32 bits, which the packet's SIMD gathers take.
    if (triangles >= kFlat) throw std::runtime_error("the scene has " + std::to_string(triangles) +
                                                     " triangles; at most 4294967294 are supported");
    m_triangles.reserve(triangles + 1);
    m_normals.reserve(smooth + 1);
    for (const Mesh &mesh : meshes) {
        RTCGeometry geom = rtcNewGeometry(m_device, RTC_GEOMETRY_TYPE_TRIANGLE);
        // Embree's own buffers are padded for its SIMD loads; ours are not, so copy.
        auto *v = static_cast<float *>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            v[3 * i] = mesh.positions[i].x;
            v[3 * i + 1] = mesh.positions[i].y;
            v[3 * i + 2] = mesh.positions[i].z;
        }
        auto *idx = static_cast<unsigned *>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                    3 * sizeof(unsigned), mesh.indices.size() / 3));
        std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
        rtcCommitGeometry(geom);
        rtcAttachGeometry(m_scene, geom);  // ids follow mesh order
        rtcReleaseGeometry(geom);
        addMaterial(bsdfs, mesh.bsdf, mesh.areaRadiance.has_value());
        m_firstTriangle.push_back(static_cast<uint32_t>(m_triangles.size()));
        m_firstNormals.push_back(mesh.normals.empty() ? kFlat : static_cast<uint32_t>(m_normals.size()));
        for (size_t f = 0; f < mesh.indices.size() / 3; ++f) {
            const uint32_t *tri = &mesh.indices[3 * f];
            const Vec3f &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];
            m_triangles.push_back({p0, p1, p2, normalize(cross(p1 - p0, p2 - p0))});
            if (!mesh.normals.empty())
                m_normals.push_back({mesh.normals[tri[0]], mesh.normals[tri[1]], mesh.normals[tri[2]]});
        }
        if (const float size = halfExtent(mesh.positions); size > 0.f) smallest = std::min(smallest, size);
    }
    m_triangles.push_back({});
    m_normals.push_back({});
    for (const Sphere &sphere : spheres) {
        attachSphere(m_device, m_scene, sphere);  // ids after the meshes'
        addMaterial(bsdfs, sphere.bsdf, sphere.areaRadiance.has_value());
        smallest = std::min(smallest, sphere.radius);
    }
    m_firstDisk = static_cast<uint32_t>(meshes.size() + spheres.size());
    m_firstCylinder = m_firstDisk + static_cast<uint32_t>(m_disks.size());
    for (const Disk &disk : m_disks) {
        attachUserGeometry(m_device, m_scene, disk);  // ids after the spheres'
        addMaterial(bsdfs, disk.bsdf, disk.areaRadiance.has_value());
        smallest = std::min(smallest, float(shapeSize(disk)));
    }
    for (const Cylinder &cylinder : m_cylinders) {
        attachUserGeometry(m_device, m_scene, cylinder);  // ids after the disks'
        addMaterial(bsdfs, cylinder.bsdf, cylinder.areaRadiance.has_value());
        smallest = std::min(smallest, float(shapeSize(cylinder)));
    }
    if (std::isfinite(smallest)) m_offsetFloor = kOffsetFloorPerSize * smallest;
    rtcCommitScene(m_scene);
    if (rtcGetDeviceError(m_device) != RTC_ERROR_NONE) {
        const std::string message = tLastError;
        rtcReleaseScene(m_scene);
        rtcReleaseDevice(m_device);
        throw std::runtime_error("cannot build the BVH: " + message);
    }
}

void EmbreeScene::addMaterial(const BsdfList &bsdfs, uint32_t index, bool emits) {
    m_emitterOf.push_back(emits ? m_areaEmitters++ : -1);
    const std::shared_ptr<const Bsdf> &bsdf = index < bsdfs.size() ? bsdfs[index] : defaultBsdf();
    m_bsdf.push_back(bsdf);
    m_textured.push_back(dynamic_cast<const TexturedBsdf *>(bsdf.get()));
    // The packet paths' tables: a side that is not Lambertian reads 0 there (its integrator refused it).
    const Color black(0.f, 0.f, 0.f);
    m_reflectance.push_back(bsdf->lambertianAlbedo(true).value_or(black));
    m_twoSided.push_back(bsdf->twoSided() ? 1 : 0);
    m_backReflectance.push_back(bsdf->twoSided() ? bsdf->lambertianAlbedo(false).value_or(black) : black);
}

const Bsdf &EmbreeScene::bsdfAt(const Hit &hit, BsdfScratch &scratch) const {
    const TexturedBsdf *textured = m_textured[hit.geom];
    return textured ? textured->at(uvAt(hit), scratch) : *m_bsdf[hit.geom];
}

Vec2f EmbreeScene::uvAt(const Hit &hit) const {
    if (hit.geom >= m_meshes.size()) return {};
    const Mesh &mesh = m_meshes[hit.geom];
    if (mesh.texcoords.empty()) return {};
    const uint32_t *corner = &mesh.indices[3 * size_t(hit.prim)];
    const Vec3f a = mesh.positions[corner[0]], b = mesh.positions[corner[1]], c = mesh.positions[corner[2]];
    // Barycentrics of p from the areas it makes with each edge, in double: p lies on the triangle.
    const Vec3f n = cross(b - a, c - a);
    const double area = dot(n, n);
    if (!(area > 0.0)) return mesh.texcoords[corner[0]];
    const double b1 = double(dot(cross(hit.p - a, c - a), n)) / area;
    const double b2 = double(dot(cross(b - a, hit.p - a), n)) / area;
    const Vec2f t0 = mesh.texcoords[corner[0]], t1 = mesh.texcoords[corner[1]], t2 = mesh.texcoords[corner[2]];
    const double b0 = 1.0 - b1 - b2;
    return {float(b0 * t0.x + b1 * t1.x + b2 * t2.x), float(b0 * t0.y + b1 * t1.y + b2 * t2.y)};
}

EmbreeScene::~EmbreeScene() {
    if (m_scene) rtcReleaseScene(m_scene);
    if (m_device) rtcReleaseDevice(m_device);
}

}  // namespace mcval
