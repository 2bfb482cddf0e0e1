#include "camera.h"

#include <cmath>

namespace mcval {

namespace {
constexpr float kDegToRad = 3.14159265358979323846f / 180.f;

/// The horizontal fov implied by `fov` along `axis` on a width x height film (Mitsuba's rules).
float horizontalFov(float fov, const std::string &axis, float width, float height) {
    const float aspect = width / height;
    std::string a = axis;
    if (a == "smaller") a = width <= height ? "x" : "y";
    if (a == "larger") a = width >= height ? "x" : "y";
    const float t = std::tan(0.5f * fov * kDegToRad);
    if (a == "y") return 2.f * std::atan(t * aspect) / kDegToRad;
    if (a == "diagonal") return 2.f * std::atan(t * width / std::sqrt(width * width + height * height)) / kDegToRad;
    return fov;
}
}  // namespace

Camera::Camera(const CameraSpec &spec, int width, int height)
    : m_orthographic(spec.projection == CameraSpec::Projection::Orthographic),
      m_origin(spec.toWorld.point({0.f, 0.f, m_orthographic ? spec.nearClip : 0.f})),
      m_fovX(m_orthographic ? 0.f : horizontalFov(spec.fov, spec.fovAxis, float(width), float(height))),
      m_tanHalfX(std::tan(0.5f * m_fovX * kDegToRad)), m_aspect(float(width) / float(height)),
      m_near(spec.nearClip), m_far(spec.farClip) {
    m_axisX = spec.toWorld.vector({1.f, 0.f, 0.f});
    m_axisY = spec.toWorld.vector({0.f, 1.f, 0.f});
    m_axisZ = spec.toWorld.vector({0.f, 0.f, 1.f});
    m_forward = normalize(m_axisZ);
    // Orthographic: the [-1, 1] x [-1/aspect, 1/aspect] square over the film, 2 / width units per pixel both ways.
    const float halfWidth = m_orthographic ? 1.f : m_tanHalfX;
    m_scaleX = 2.f * halfWidth / float(width);
    m_scaleY = 2.f * halfWidth / m_aspect / float(height);
    // Mitsuba's principal_point_offset: film position (x, y) looks where (x + ox width, y + oy height) would.
    m_left = m_tanHalfX - spec.principalOffsetX * float(width) * m_scaleX;
    m_top = m_tanHalfX / m_aspect - spec.principalOffsetY * float(height) * m_scaleY;
}

}  // namespace mcval
