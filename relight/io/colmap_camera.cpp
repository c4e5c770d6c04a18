#include "relight/io/colmap_camera.h"

#include <algorithm>
#include <cmath>

#include "relight/errors.h"

namespace relight::colmap {

glm::dmat3 rotationFromQuaternion(const std::array<double, 4>& q, const std::string& where) {
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    // A written unit quaternion is off by rounding only; one near zero is no rotation.
    if (!(norm > 1e-6)) throw InputError(where + ": the quaternion QVEC is zero (no rotation)");
    const double w = q[0] / norm, x = q[1] / norm, y = q[2] / norm, z = q[3] / norm;
    const double rows[3][3] = {
        {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
        {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
        {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)},
    };
    glm::dmat3 R;  // glm is column-major: R[col][row]
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) R[c][r] = rows[r][c];
    return R;
}

std::array<double, 4> quaternionFromRotation(const glm::dmat3& m) {
    auto at = [&](int r, int c) { return m[c][r]; };
    const double trace = at(0, 0) + at(1, 1) + at(2, 2);
    // 4 w^2 = 1 + trace, 4 x^2 = 1 + 2 R00 - trace, ...: start from the largest, which is
    // at least 1/4, so its square root is at least 1/2 and the divisions below are safe.
    const double sq[4] = {1 + trace, 1 + 2 * at(0, 0) - trace, 1 + 2 * at(1, 1) - trace,
                          1 + 2 * at(2, 2) - trace};
    const int k = static_cast<int>(std::max_element(sq, sq + 4) - sq);
    const double s = 0.5 * std::sqrt(sq[k]);  // the component k itself
    const double d = 0.25 / s;
    std::array<double, 4> q{};
    if (k == 0)
        q = {s, (at(2, 1) - at(1, 2)) * d, (at(0, 2) - at(2, 0)) * d, (at(1, 0) - at(0, 1)) * d};
    else if (k == 1)
        q = {(at(2, 1) - at(1, 2)) * d, s, (at(0, 1) + at(1, 0)) * d, (at(0, 2) + at(2, 0)) * d};
    else if (k == 2)
        q = {(at(0, 2) - at(2, 0)) * d, (at(0, 1) + at(1, 0)) * d, s, (at(1, 2) + at(2, 1)) * d};
    else
        q = {(at(1, 0) - at(0, 1)) * d, (at(0, 2) + at(2, 0)) * d, (at(1, 2) + at(2, 1)) * d, s};
    if (q[0] < 0)
        for (double& c : q) c = -c;
    return q;
}

void Lens::distort(double x, double y, double& xd, double& yd) const {
    const double x2 = x * x, y2 = y * y, xy = x * y, r2 = x2 + y2;
    const double radial = k1 * r2 + k2 * r2 * r2;
    xd = x + x * radial + 2 * p1 * xy + p2 * (r2 + 2 * x2);
    yd = y + y * radial + 2 * p2 * xy + p1 * (r2 + 2 * y2);
}

bool Lens::undistort(double xd, double yd, double& xOut, double& yOut) const {
    double x = xd, y = yd;
    // Converged when distort(x, y) meets (xd, yd) to within a few roundings of its terms.
    const double tolerance = 1e-14 * (1 + std::abs(xd) + std::abs(yd));
    for (int it = 0; it < 50; ++it) {
        double xr = 0, yr = 0;
        distort(x, y, xr, yr);
        const double ex = xr - xd, ey = yr - yd;
        // The Jacobian of distort(), analytically.
        const double r2 = x * x + y * y, radial = k1 * r2 + k2 * r2 * r2;
        const double dRadial = 2 * (k1 + 2 * k2 * r2);  // d radial / d x = x dRadial
        const double a = 1 + radial + x * x * dRadial + 2 * p1 * y + 6 * p2 * x;
        const double b = x * y * dRadial + 2 * p1 * x + 2 * p2 * y;
        const double c = x * y * dRadial + 2 * p2 * y + 2 * p1 * x;
        const double d = 1 + radial + y * y * dRadial + 2 * p2 * x + 6 * p1 * y;
        const double det = a * d - b * c;
        // det <= 0: the distortion folds back here, where no point has a unique inverse.
        if (!(det > 1e-12)) return false;
        if (std::abs(ex) + std::abs(ey) <= tolerance) {
            xOut = x;
            yOut = y;
            return true;
        }
        x -= (d * ex - b * ey) / det;
        y -= (a * ey - c * ex) / det;
    }
    return false;
}

Lens lensOf(const Camera& camera) {
    const std::vector<double>& p = camera.params;
    Lens l;
    l.width = static_cast<int>(camera.width);
    l.height = static_cast<int>(camera.height);
    double ccx = 0, ccy = 0;  // COLMAP's principal point
    if (camera.model == "SIMPLE_PINHOLE" || camera.model == "SIMPLE_RADIAL" ||
        camera.model == "RADIAL") {
        l.fx = l.fy = p[0];
        ccx = p[1];
        ccy = p[2];
        if (camera.model != "SIMPLE_PINHOLE") l.k1 = p[3];
        if (camera.model == "RADIAL") l.k2 = p[4];
    } else if (camera.model == "PINHOLE" || camera.model == "OPENCV") {
        l.fx = p[0];
        l.fy = p[1];
        ccx = p[2];
        ccy = p[3];
        if (camera.model == "OPENCV") {
            l.k1 = p[4];
            l.k2 = p[5];
            l.p1 = p[6];
            l.p2 = p[7];
        }
    } else {
        throw InputError(camera.where + ": camera model " + camera.model +
                         " is not supported (SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL and "
                         "OPENCV are); undistort the images first with `colmap "
                         "image_undistorter --image_path IMAGES --input_path SPARSE "
                         "--output_path DENSE` and import DENSE/sparse with DENSE/images");
    }
    if (!(l.fx > 0 && l.fy > 0))
        throw InputError(camera.where + ": the focal length must be positive");
    // COLMAP's pixel (0.5, 0.5) is the centre of the top-left pixel, the format's (0, 0).
    l.cx = ccx - 0.5;
    l.cy = ccy - 0.5;
    return l;
}

relight::Camera sceneCamera(const Image& image, const Lens& lens) {
    relight::Camera c;
    c.width = lens.width;
    c.height = lens.height;
    c.fx = lens.fx;
    c.fy = lens.fy;
    c.cx = lens.cx;
    c.cy = lens.cy;
    c.cameraFromWorldR = rotationFromQuaternion(image.qvec, image.where);
    c.cameraFromWorldT = Vec3(image.tvec[0], image.tvec[1], image.tvec[2]);
    return c;
}

Camera colmapCamera(const relight::Camera& camera, int64_t id) {
    Camera c;
    c.id = id;
    c.model = "PINHOLE";
    c.width = camera.width;
    c.height = camera.height;
    c.params = {camera.fx, camera.fy, camera.cx + 0.5, camera.cy + 0.5};
    return c;
}

Image colmapImage(const relight::Camera& camera, int64_t id, int64_t cameraId,
                  const std::string& name) {
    Image im;
    im.id = id;
    im.qvec = quaternionFromRotation(camera.cameraFromWorldR);
    im.tvec = {camera.cameraFromWorldT.x, camera.cameraFromWorldT.y, camera.cameraFromWorldT.z};
    im.cameraId = cameraId;
    im.name = name;
    return im;
}

}  // namespace relight::colmap
