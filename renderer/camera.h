// Mitsuba's perspective camera: same fov axis, orientation, pixel centres and near clip.
#pragma once

#include "ray.h"
#include "scene.h"

namespace mcval {

class Camera {
public:
    Camera(const CameraSpec &spec, int width, int height);

    /// The primary ray through film position (x, y) in pixels: (0, 0) is the top-left corner
    /// of the image, pixel (i, j) covers [i, i+1] x [j, j+1]. Starts at the near clip plane.
    Ray generateRay(float x, float y) const;

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
