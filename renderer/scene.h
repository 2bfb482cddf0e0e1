// What a scene file describes, after loading: plain data, in world space.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "affine.h"
#include "bsdfs/bsdf.h"
#include "textures/texture.h"
#include "sampler.h"
#include "transform.h"
#include "vector.h"

namespace mcval {


/// A triangle mesh in world space with its BSDF.
struct Mesh {
    std::string name;                ///< what the scene called it (for messages)
    std::vector<Vec3f> positions;
    std::vector<Vec3f> normals;      ///< per vertex; empty for flat shading
    /// Per vertex, Mitsuba's (u, v): an OBJ's vt with v turned upside down (row 0 of an image at v = 0), a
    /// rectangle's corners at 0 and 1; empty where the file gives none.
    std::vector<Vec2f> texcoords;
    std::vector<uint32_t> indices;   ///< three per triangle, counter-clockwise seen from the front
    uint32_t bsdf = 0;               ///< its BSDF: an index into SceneDescription::bsdfs (0: the default)
    std::optional<Color> areaRadiance;     ///< its <emitter type="area">'s radiance, where the integrator reads it
};

/// Mitsuba's `sphere` in world space, intersected exactly rather than tessellated.
struct Sphere {
    std::string name;                ///< what the scene called it (for messages)
    Vec3f center;
    float radius = 1.f;
    bool flipNormals = false;        ///< front side inside: flip_normals, or a mirroring to_world (as Mitsuba)
    uint32_t bsdf = 0;               ///< its BSDF: an index into SceneDescription::bsdfs (0: the default)
    std::optional<Color> areaRadiance;     ///< its <emitter type="area">'s radiance, where the integrator reads it
};

/// Mitsuba's `disk`: the unit disk at z = 0 of object space under an affine to_world, intersected exactly.
struct Disk {
    std::string name;                ///< what the scene called it (for messages)
    Affine toWorld;
    bool flipNormals = false;        ///< flip_normals: the front is object-space -z
    uint32_t bsdf = 0;               ///< its BSDF: an index into SceneDescription::bsdfs (0: the default)
    std::optional<Color> areaRadiance;     ///< its <emitter type="area">'s radiance, where the integrator reads it
};

/// Mitsuba's `cylinder`: the open unit cylinder (radius 1, z in [0, 1]) of object space under
/// `toWorld`, which already holds p0, p1 and radius (to_world * translate(p0) * frame * scale).
struct Cylinder {
    std::string name;                ///< what the scene called it (for messages)
    Affine toWorld;
    bool flipNormals = false;        ///< flip_normals: the normals point inward
    uint32_t bsdf = 0;               ///< its BSDF: an index into SceneDescription::bsdfs (0: the default)
    std::optional<Color> areaRadiance;     ///< its <emitter type="area">'s radiance, where the integrator reads it
};

/// An isotropic point light; intensity in W/sr.
struct PointLight {
    Vec3f position;
    Color intensity;
};

/// Mitsuba's `spot`: a point light at to_world's origin shining along its +z; intensity in W/sr on the axis.
struct SpotLight {
    Transform toWorld;
    Color intensity{1.f, 1.f, 1.f};
    float cutoffAngle = 20.f;        ///< degrees: no light beyond
    float beamWidth = 15.f;          ///< degrees: full intensity within (Mitsuba's default: 3/4 of the cutoff)
    /// Mitsuba's `texture`: an image projected over the cone, (u, v) = 1/2 + (x, y) / (2 z tan(cutoff)) in the
    /// light's frame; none: white.
    std::shared_ptr<const Texture> texture;
};

/// Mitsuba's `directional`: light from infinitely far away along one direction; irradiance in W/m^2.
struct DirectionalLight {
    Vec3f direction{0.f, 0.f, 1.f};  ///< where the light travels (unit)
    Color irradiance{1.f, 1.f, 1.f};
};

/// Mitsuba's `envmap`: radiance from a latitude-longitude image (u = atan2(x, -z) / 2 pi, v = acos(y) / pi in
/// the frame of to_world, a rotation), infinitely far away.
struct EnvironmentMap {
    std::shared_ptr<const RgbImage> image;  ///< at least 2 x 3 pixels, finite and non-negative
    Transform toWorld;
    float scale = 1.f;
};

/// Mitsuba's `perspective` or `orthographic` sensor.
struct CameraSpec {
    /// orthographic: parallel rays along to_world's +z from the [-1, 1] x [-1/aspect, 1/aspect] square.
    enum class Projection { Perspective, Orthographic } projection = Projection::Perspective;
    Transform toWorld;
    float fov = 0.f;                 ///< degrees, along fovAxis (perspective only)
    std::string fovAxis = "x";       ///< x, y, diagonal, smaller, larger
    /// principal_point_offset_x/y (perspective only): the principal point's offset from the film's centre,
    /// in film widths and heights.
    float principalOffsetX = 0.f, principalOffsetY = 0.f;
    float nearClip = 1e-2f;
    float farClip = 1e4f;
};

/// Reconstruction filter: `box` (radius 0.5), `gaussian` (stddev 0.5, radius 4 stddev) or `tent`
/// (max(0, 1 - |x| / radius), radius 1).
struct FilterSpec {
    enum class Type { Box, Gaussian, Tent } type = Type::Gaussian;
    float stddev = 0.5f;
    float tentRadius = 1.f;
    float radius() const { return type == Type::Box ? 0.5f : type == Type::Tent ? tentRadius : 4.f * stddev; }
};

struct FilmSpec {
    int width = 768, height = 576;   ///< Mitsuba's hdrfilm defaults
    /// hdrfilm's crop window: the image is pixels [cropX, cropX + cropWidth) x [cropY, cropY + cropHeight) of
    /// the width x height film, whose size the camera's projection keeps. The whole film by default.
    int cropX = 0, cropY = 0, cropWidth = 768, cropHeight = 576;
    /// hdrfilm's sample_border: pixels as far outside the crop window as the filter reaches are sampled too,
    /// so that its edge pixels get the samples around them that an inner pixel gets.
    bool sampleBorder = false;
    FilterSpec filter;
    std::string componentFormat = "float32";  ///< hdrfilm component_format: float16 or float32
};

class Integrator;
class EmbreeScene;
struct SceneDescription;
/// Builds an integrator, configured by its own parameters, for one scene.
using IntegratorMaker = std::function<std::unique_ptr<Integrator>(const SceneDescription &, const EmbreeScene &)>;

/// Which of our integrators to run, and its parameters as the integrator itself parsed them.
struct IntegratorSpec {
    std::string type;
    IntegratorMaker make;            ///< empty: the integrator's defaults
};

/// Everything the renderer needs from a scene file.
struct SceneDescription {
    std::string file;
    CameraSpec camera;
    FilmSpec film;
    int sampleCount = 4;             ///< Mitsuba's `independent` default
    SamplerType sampler = SamplerType::Independent;  ///< <sampler type="...">
    std::vector<Mesh> meshes;
    std::vector<Sphere> spheres;
    std::vector<Disk> disks;
    std::vector<Cylinder> cylinders;
    /// The BSDFs the shapes name; the first is Mitsuba's default (diffuse, reflectance 0.5), a shape's without one.
    BsdfList bsdfs = defaultBsdfs();
    std::vector<PointLight> pointLights;
    std::vector<SpotLight> spotLights;                ///< read where the integrator reads spot lights
    std::vector<DirectionalLight> directionalLights;  ///< read where the integrator reads directional lights
    std::optional<Color> environment;  ///< radiance of the `constant` emitter, if any
    std::optional<EnvironmentMap> envmap;  ///< read where the integrator reads envmaps; never with `environment`
    /// The file's <integrator>'s `hide_emitters`, whatever its type (nested ones included): every Mitsuba
    /// integrator reads it with one meaning, so it holds for the chosen integrator too. Unset: not given.
    std::optional<bool> hideEmitters;
    IntegratorSpec integrator;
};

/// Loads a scene file of the Mitsuba 3 XML subset; `params` override its <default> values.
/// Throws SceneError naming file, line and what was expected.
/// `integrator`, if not empty, overrides the file's <integrator> whatever its type; elements the
/// chosen integrator does not use are skipped with one note line on stderr, those that would
/// change its answer are errors.
SceneDescription loadScene(const std::string &path, const std::map<std::string, std::string> &params = {},
                           const std::string &integrator = "");

}  // namespace mcval
