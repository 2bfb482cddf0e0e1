// Mitsuba's perspective camera: same fov axis, orientation, pixel centres and near clip.
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
    /// Inline: the renderer writes it straight into its packet, with no copy through the stack.
    Ray generateRay(float x, float y) const {
        // Camera space: +z forward, +x to the left, +y up; the left edge of the image is +x. The
        // direction is (lx, ly, 1) in camera space, normalised once in world space.
        const float lx = m_tanHalfX - x * m_scaleX, ly = m_tanHalfX / m_aspect - y * m_scaleY;
        const float length = std::sqrt(lx * lx + ly * ly + 1.f);
        Ray ray;
        ray.o = m_origin;
        ray.d = normalize(m_axisX * lx + m_axisY * ly + m_axisZ);
        ray.tnear = m_near * length;  // clip planes are distances along the optical axis
        ray.tfar = m_far * length;
        return ray;
    }

    /// The horizontal field of view in degrees, whatever axis the scene gave.
    float fovX() const { return m_fovX; }

private:
    Transform m_toWorld;
    Vec3f m_origin;
    float m_fovX, m_tanHalfX, m_aspect, m_width, m_height, m_near, m_far;
    Vec3f m_axisX, m_axisY, m_axisZ;  ///< the camera's axes in world space (to_world's columns)
    float m_scaleX, m_scaleY;         ///< camera-space units per pixel
};

}  // namespace mcval
