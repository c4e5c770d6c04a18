// Camera: a pinhole camera in the OpenCV convention of the scene format
// (docs/scene-format.md, "camera").
//
// A world point X has camera coordinates Xc = R X + t; pixel (u, v) = (fx Xc/Zc + cx,
// fy Yc/Zc + cy), where (0, 0) is the centre of the top-left pixel, +u right, +v down.
#pragma once

#include <glm/mat3x3.hpp>

#include "radiosity/vec.h"

namespace relight {

using radiosity::Vec3;

struct Camera {
    int width = 0, height = 0;  ///< image size in pixels
    double fx = 1, fy = 1;      ///< focal lengths in pixels
    double cx = 0, cy = 0;  ///< principal point in pixels (OpenCV: centre of pixel (0,0) is 0,0)
    glm::dmat3 cameraFromWorldR{1.0};  ///< R of world_to_camera (rotation)
    Vec3 cameraFromWorldT{0, 0, 0};    ///< t of world_to_camera (metres)

    /// Camera centre in world space (metres): -R^T t.
    Vec3 position() const;
    /// Unit world-space direction of the ray through image point (u, v) (pixels).
    Vec3 rayDirection(double u, double v) const;
    /// Projects a world point; returns false when it lies behind the camera (Zc <= 0).
    bool project(const Vec3& world, double& u, double& v, double& depth) const;
};

}  // namespace relight
