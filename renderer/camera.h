// Mitsuba's perspective and orthographic cameras: same fov axis, orientation, pixel centres and clip planes.
#pragma once

#include <cmath>

#include "ray.h"
#include "scene.h"

namespace mcval {

class Camera {
public:
    Camera(const CameraSpec &spec, int width, int height);

    /// The primary ray through film position (x, y) in pixels: (0, 0) is the top-left corner
    /// of the image, pixel (i, j) covers [i, i+1] x [j, j+1]. Starts at the near clip plane.
    Ray generateRay(float x, float y) const {
        float length;
        Ray ray;
        if (m_orthographic) {
            ray.o = orthographicOrigin(x, y);
            ray.d = m_forward;
            ray.tnear = 0.f;
            ray.tfar = m_far - m_near;  // Mitsuba's maxt: the clip planes' distance, in world units
            return ray;
        }
        ray.o = m_origin;
        ray.d = direction(x, y, length);
        ray.tnear = m_near * length;  // clip planes are distances along the optical axis
        ray.tfar = m_far * length;
        return ray;
    }

    /// generateRay's direction; `length` is the camera-space length of (lx, ly, 1), by which the
    /// clip distances scale. Inline and branch-free: the renderer computes a packet's in SIMD.
    Vec3f direction(float x, float y, float &length) const {
        // Camera space: +z forward, +x to the left, +y up; the left edge of the image is +x. The
        // direction is (lx, ly, 1) in camera space, normalised once in world space.
        const float lx = m_left - x * m_scaleX, ly = m_top - y * m_scaleY;
        length = std::sqrt(lx * lx + ly * ly + 1.f);
        return normalize(m_axisX * lx + m_axisY * ly + m_axisZ);
    }

    /// The orthographic ray's origin for film position (x, y): to_world applied to (lx, ly, near_clip),
    /// where lx runs over [1, -1] across the width and ly over [1/aspect, -1/aspect] down the height
    /// (Mitsuba's orthographic_projection: the film's width spans two units). Inline: see direction().
    Vec3f orthographicOrigin(float x, float y) const {
        const float lx = 1.f - x * m_scaleX, ly = 1.f / m_aspect - y * m_scaleY;
        return m_origin + m_axisX * lx + m_axisY * ly;
    }
    /// Whether rays are parallel (orthographic); their direction is forward().
    bool orthographic() const { return m_orthographic; }
    /// The orthographic rays' unit direction: to_world's +z.
    Vec3f forward() const { return m_forward; }

    /// The perspective camera's centre; the orthographic camera's near-plane centre.
    Vec3f origin() const { return m_origin; }
    float nearClip() const { return m_near; }
    float farClip() const { return m_far; }

    /// The horizontal field of view in degrees, whatever axis the scene gave (perspective only).
    float fovX() const { return m_fovX; }

private:
    bool m_orthographic;
    Vec3f m_origin, m_forward;
    float m_fovX, m_tanHalfX, m_aspect, m_near, m_far;
    /// Perspective: camera-space x and y (at unit distance) of the film's top-left corner, moved by the
    /// principal point's offset.
    float m_left = 0.f, m_top = 0.f;
    Vec3f m_axisX, m_axisY, m_axisZ;  ///< the camera's axes in world space (to_world's columns)
    float m_scaleX, m_scaleY;         ///< camera-space units per pixel (at unit distance, for perspective)
};

}  // namespace mcval
