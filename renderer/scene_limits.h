// The ranges every scene number must lie in: finite, meaningful, and with bounded work.
#pragma once

namespace mcval {

/// Largest |coordinate| of a world-space position or light: far inside Embree's limit (1.8e18),
/// with room for the differences and squared distances the integrators take.
constexpr float kMaxCoordinate = 1e15f;
/// Smallest sphere radius: its squares (1e-30) stay normal float32 numbers.
constexpr float kMinSphereRadius = 1e-15f;
/// Smallest sphere radius relative to its centre's largest coordinate: float32 places a hit point to
/// 1.2e-7 of that coordinate, so the point stays within 1e-3 of the radius of the surface.
constexpr float kMinSphereRadiusToCenter = 1e-4f;
/// Largest emitted intensity (W/sr) or radiance: products with 1/r^2 stay finite in float32.
constexpr float kMaxEmission = 1e15f;
/// Largest film side in pixels.
constexpr int kMaxFilmSide = 16384;
/// Largest memory the film and the output images of one render may take, in bytes.
constexpr double kMaxImageBytes = 8.0 * (1ll << 30);
/// Largest samples per pixel (per batch), from the scene or the command line.
constexpr int kMaxSampleCount = 1 << 20;
/// Largest number of independent batches of one render: its EXR holds 3 channels per batch plus the mean
/// and the variance, and OpenImageIO's EXR reader (the harness's) takes at most 4096 channels.
constexpr int kMaxBatches = 1363;
/// Largest number of occlusion rays per `ao` camera sample.
constexpr int kMaxAoSamples = 1024;
/// Range of a gaussian filter's standard deviation, in pixels: narrower underflows its weights,
/// wider splats each sample over thousands of pixels (Mitsuba's default is 0.5).
constexpr float kMinFilterStddev = 0.05f, kMaxFilterStddev = 4.f;
/// Range of a tent filter's radius, in pixels: the gaussian's radii (4 stddev).
constexpr float kMinTentRadius = 4.f * kMinFilterStddev, kMaxTentRadius = 4.f * kMaxFilterStddev;
/// Largest |principal_point_offset_x| or |principal_point_offset_y|, in film widths and heights.
constexpr float kMaxPrincipalOffset = 10.f;
/// Range of the field of view, in degrees: Mitsuba's (0, 180), less what float cannot tell from its ends (Nori's
/// test scenes look along one ray with a fov of 1e-6).
constexpr float kMinFov = 1e-7f, kMaxFov = 179.9f;
/// Largest scene file read, in bytes.
constexpr long long kMaxSceneFileBytes = 64ll << 20;

}  // namespace mcval
