// The homography between a plane of the model and the photo (issue 34: the rectified fill,
// relight/dynamic/rectified_fill.h). For a pinhole camera x ~ K [R | t] X, a point of the
// plane X = o + a u + b w (o a point of the plane, u and w orthonormal in it, a and b in
// metres) projects as
//   x ~ K [R u | R w | R o + t] (a, b, 1)^T = H (a, b, 1)^T
// (Hartley & Zisserman 2004, §8.1.1: the homography induced by a world plane). The third
// row of H gives the camera-space depth of the point (K's third row is (0, 0, 1)): a point
// with w <= 0 lies behind the camera and has no pixel. Only rectified_fill.cpp and its test
// include this header (OpenCV reaches no other target).
#pragma once

#include <opencv2/core/matx.hpp>

#include "radiosity/vec.h"
#include "relight/pipeline/camera.h"

namespace relight {

/// A plane's 2D frame: a point of it and two orthonormal directions in it.
struct PlaneFrame {
    radiosity::Vec3 origin{0, 0, 0}, u{1, 0, 0}, v{0, 1, 0};
};

/// H, mapping plane coordinates (a, b, 1) in metres to homogeneous pixel coordinates.
cv::Matx33d planeToImage(const Camera& camera, const PlaneFrame& plane);

/// (x, y) = H (a, b, 1) dehomogenised; false when the homogeneous w is not positive (for
/// planeToImage's H: the point lies behind the camera, or on its focal plane).
bool applyHomography(const cv::Matx33d& H, double a, double b, double& x, double& y);

}  // namespace relight
