// The plane homography of the rectified fill (relight/dynamic/plane_homography.h): it maps a
// plane's points to the pixels the camera projects them to, it agrees with OpenCV's
// cv::findHomography fitted to four of those projections, and it refuses points behind the
// camera.
#include "relight/dynamic/plane_homography.h"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "relight/io/scene_file.h"

namespace relight {
namespace {

using radiosity::Vec3;

/// The room's camera (data/room/scene.json): a real K and pose, not an identity.
Camera roomCamera() {
    return loadScene(RELIGHT_DATA_DIR "/room").camera;
}

/// A plane through `origin` with normal `n` and an orthonormal frame in it.
PlaneFrame frameOf(const Vec3& origin, const Vec3& n) {
    const Vec3 nn = glm::normalize(n);
    const Vec3 axis = std::abs(nn.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 u = glm::normalize(axis - glm::dot(axis, nn) * nn);
    return {origin, u, glm::cross(nn, u)};
}

TEST(PlaneHomography, MapsPlanePointsToTheirCameraProjection) {
    const Camera camera = roomCamera();
    std::mt19937 rng(34);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    int compared = 0;
    for (int plane = 0; plane < 50; ++plane) {
        const PlaneFrame f = frameOf({3 * unit(rng), 3 * unit(rng), 1.5 + unit(rng)},
                                     {unit(rng), unit(rng), unit(rng) + 1e-3});
        const cv::Matx33d H = planeToImage(camera, f);
        for (int i = 0; i < 200; ++i) {
            const double a = 4 * unit(rng), b = 4 * unit(rng);
            const Vec3 x = f.origin + a * f.u + b * f.v;
            double pu = 0, pv = 0, depth = 0, hu = 0, hv = 0;
            const bool seen = camera.project(x, pu, pv, depth);
            // w is the depth: the homography refuses what the camera cannot see.
            ASSERT_EQ(applyHomography(H, a, b, hu, hv), seen);
            if (!seen || depth < 0.05) continue;  // near the focal plane pixels run to 1e5
            // The same product in another order, in double: pixel coordinates of at most a few
            // thousand carry rounding of about 1e-12; 1e-7 pixel leaves room for the division
            // by a depth of 5 cm.
            EXPECT_NEAR(hu, pu, 1e-7);
            EXPECT_NEAR(hv, pv, 1e-7);
            ++compared;
        }
    }
    EXPECT_GT(compared, 2000);  // not vacuous: most of the points lie in front
}

TEST(PlaneHomography, AgreesWithFindHomographyOnFourCorners) {
    // The room's back wall and floor (y = 3, z = 0 in data/room): four corners of a 1 m
    // square on each, projected by the camera, fitted by OpenCV; the fit of four exact
    // correspondences is the homography up to scale (8 unknowns, 8 equations).
    const Camera camera = roomCamera();
    for (const PlaneFrame& f : {PlaneFrame{{1, 3, 0.5}, {1, 0, 0}, {0, 0, 1}},
                                PlaneFrame{{1.5, 2, 0}, {1, 0, 0}, {0, 1, 0}}}) {
        std::vector<cv::Point2d> plane, image;
        for (const auto& [a, b] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}}) {
            double pu = 0, pv = 0, d = 0;
            ASSERT_TRUE(camera.project(f.origin + a * f.u + b * f.v, pu, pv, d));
            plane.emplace_back(a, b);
            image.emplace_back(pu, pv);
        }
        const cv::Mat fit = cv::findHomography(plane, image);
        ASSERT_FALSE(fit.empty());
        const cv::Matx33d H = planeToImage(camera, f);
        const cv::Matx33d F(fit.ptr<double>());
        // Both map the square's points to the same pixels. Tolerance: OpenCV's fit carries
        // about float precision (measured: entries 3e-6 relative off H's), which moves a
        // pixel of the 320 x 240 photo by about 1e-4: 1e-3 pixel.
        for (double a = 0; a <= 1.0; a += 0.25)
            for (double b = 0; b <= 1.0; b += 0.25) {
                double hu = 0, hv = 0, fu = 0, fv = 0;
                ASSERT_TRUE(applyHomography(H, a, b, hu, hv));
                const cv::Vec3d q = F * cv::Vec3d(a, b, 1);
                fu = q[0] / q[2];
                fv = q[1] / q[2];
                EXPECT_NEAR(fu, hu, 1e-3);
                EXPECT_NEAR(fv, hv, 1e-3);
            }
    }
}

TEST(PlaneHomography, ItsInverseMeetsThePlaneWhereTheRayDoes) {
    // Back from a pixel: H^-1 gives the plane coordinates of the point the pixel's camera ray
    // meets, as a ray-plane intersection does (rectified_fill.cpp reads its texture there).
    const Camera camera = roomCamera();
    const PlaneFrame f{{0, 3, 0}, {1, 0, 0}, {0, 0, 1}};  // the back wall, y = 3
    const cv::Matx33d Hinv = planeToImage(camera, f).inv();
    const Vec3 n = glm::cross(f.u, f.v), eye = camera.position();
    for (double y = 10; y < 120; y += 13)
        for (double x = 5; x < 315; x += 17) {
            const Vec3 dir = camera.rayDirection(x, y);
            const double t = glm::dot(f.origin - eye, n) / glm::dot(dir, n);
            if (!(t > 0)) continue;
            const Vec3 hit = eye + t * dir;
            const cv::Vec3d p = Hinv * cv::Vec3d(x, y, 1);
            // Metres on a wall a few metres away; both in double: 1e-9 m.
            EXPECT_NEAR(p[0] / p[2], glm::dot(hit - f.origin, f.u), 1e-9);
            EXPECT_NEAR(p[1] / p[2], glm::dot(hit - f.origin, f.v), 1e-9);
        }
}

}  // namespace
}  // namespace relight
