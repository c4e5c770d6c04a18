// From a COLMAP camera and image to the scene format's camera (docs/scene-format.md,
// "camera"), with the conventions converted exactly:
//   - pose: COLMAP's (qvec, tvec) is world-to-camera, x_cam = R(q) x_world + t, which is the
//     format's world_to_camera = [R(q) | t] as it is (both look along +z, x right, y down);
//   - principal point: COLMAP puts the centre of the top-left pixel at (0.5, 0.5), the format
//     at (0, 0), so cx = cx_colmap - 0.5 and cy = cy_colmap - 0.5.
// The lens models the importer takes, with COLMAP's parameter order:
//   SIMPLE_PINHOLE f, cx, cy                PINHOLE fx, fy, cx, cy
//   SIMPLE_RADIAL  f, cx, cy, k             RADIAL  f, cx, cy, k1, k2
//   OPENCV         fx, fy, cx, cy, k1, k2, p1, p2
// The other models (fisheye, FOV, thin prism) are refused by name.
#pragma once

#include <array>
#include <string>

#include "relight/io/colmap_model.h"
#include "relight/pipeline/camera.h"

namespace relight::colmap {

/// The rotation R(q) of a quaternion w, x, y, z (Hamilton), normalised first as COLMAP does.
/// Throws InputError "<where>: ..." when q is (nearly) zero and has no rotation.
glm::dmat3 rotationFromQuaternion(const std::array<double, 4>& q, const std::string& where);

/// The unit quaternion w, x, y, z (w >= 0) of a rotation matrix (Shepperd's method: the
/// largest of the four squared components is found first, so no division is by a small
/// number).
std::array<double, 4> quaternionFromRotation(const glm::dmat3& R);

/// A camera's intrinsics in the format's pixel convention (pixel centres at integers) and its
/// lens distortion in COLMAP's form: a point (x, y) = (Xc/Zc, Yc/Zc) is seen at
///   u = fx (x + dx) + cx,   v = fy (y + dy) + cy,   r2 = x^2 + y^2,
///   dx = x (k1 r2 + k2 r2^2) + 2 p1 x y + p2 (r2 + 2 x^2),
///   dy = y (k1 r2 + k2 r2^2) + 2 p2 x y + p1 (r2 + 2 y^2),
/// which is each of the five models above with the parameters it lacks at zero.
struct Lens {
    int width = 0, height = 0;
    double fx = 1, fy = 1, cx = 0, cy = 0;
    double k1 = 0, k2 = 0, p1 = 0, p2 = 0;

    bool distorted() const { return k1 != 0 || k2 != 0 || p1 != 0 || p2 != 0; }
    /// (x, y) -> (x + dx, y + dy).
    void distort(double x, double y, double& xd, double& yd) const;
    /// The inverse of distort() by Newton's method from (xd, yd); false when it does not
    /// converge (a point beyond where the distortion folds back) and x, y are then unset.
    bool undistort(double xd, double yd, double& x, double& y) const;
};

/// The lens of a COLMAP camera. Throws InputError naming camera.where for a model other
/// than the five above, and for a focal length that is not positive.
Lens lensOf(const Camera& camera);

/// The scene-format camera of `image` seen through the pinhole `lens` (its distortion
/// ignored: the caller undistorts the photo first).
relight::Camera sceneCamera(const Image& image, const Lens& lens);

/// The COLMAP PINHOLE camera and image of a scene-format camera (the tests' round trips).
Camera colmapCamera(const relight::Camera& camera, int64_t id);
Image colmapImage(const relight::Camera& camera, int64_t id, int64_t cameraId,
                  const std::string& name);

}  // namespace relight::colmap
