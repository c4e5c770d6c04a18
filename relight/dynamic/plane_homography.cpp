#include "relight/dynamic/plane_homography.h"

namespace relight {

cv::Matx33d planeToImage(const Camera& camera, const PlaneFrame& plane) {
    // K [R u | R w | R o + t] (plane_homography.h). glm's matrices are column-major:
    // cameraFromWorldR * x is R x.
    const glm::dmat3& R = camera.cameraFromWorldR;
    const radiosity::Vec3 c0 = R * plane.u, c1 = R * plane.v,
                          c2 = R * plane.origin + camera.cameraFromWorldT;
    const cv::Matx33d K(camera.fx, 0, camera.cx, 0, camera.fy, camera.cy, 0, 0, 1);
    const cv::Matx33d M(c0.x, c1.x, c2.x, c0.y, c1.y, c2.y, c0.z, c1.z, c2.z);
    return K * M;
}

bool applyHomography(const cv::Matx33d& H, double a, double b, double& x, double& y) {
    const cv::Vec3d p = H * cv::Vec3d(a, b, 1.0);
    if (!(p[2] > 0)) return false;
    x = p[0] / p[2];
    y = p[1] / p[2];
    return true;
}

}  // namespace relight
