#include "relight/pipeline/camera.h"

#include <glm/matrix.hpp>

namespace relight {

Vec3 Camera::position() const {
    return -(glm::transpose(cameraFromWorldR) * cameraFromWorldT);
}

Vec3 Camera::rayDirection(double u, double v) const {
    // Invert the pinhole projection at depth Zc = 1, then rotate back to world: R^T Xc.
    const Vec3 dirCamera{(u - cx) / fx, (v - cy) / fy, 1.0};
    return glm::normalize(glm::transpose(cameraFromWorldR) * dirCamera);
}

bool Camera::project(const Vec3& world, double& u, double& v, double& depth) const {
    const Vec3 xc = cameraFromWorldR * world + cameraFromWorldT;
    depth = xc.z;
    if (!(xc.z > 0)) return false;
    u = fx * xc.x / xc.z + cx;
    v = fy * xc.y / xc.z + cy;
    return true;
}

}  // namespace relight
