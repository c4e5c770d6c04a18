// Sky transfer (radiosity/sky_transfer.h): unoccluded points against A_l Y_k(n), a point
// under an overhang (a horizontal half-plane) against the integral over the sky it sees,
// the occluded irradiance as a dot product, determinism, and bad input.
#include "radiosity/sky_transfer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace radiosity {
namespace {

constexpr double kPi = std::numbers::pi;

void addQuad(Scene& s, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const std::vector<Vec3> corners{a, b, c, d};
    ASSERT_EQ(checkPolygon(corners).status, PolygonCheck::Status::ok);
    s.polygons.push_back(makePolygon(corners, 0, Rgb::gray(0.5)));
}

// The ground z = 0 (polygon 0, facing up) and an overhang at height h over x > 0
// (polygon 1, facing down), both W metres across: "infinite" for a point near the origin,
// as they miss only directions below atan(h / W) of the horizon, whose cosine-weighted
// share of the sky is below (h / W)^2 = 1e-8.
Scene overhangScene(double h, double W) {
    Scene s;
    s.objects.push_back("courtyard");
    addQuad(s, {-W, -W, 0}, {W, -W, 0}, {W, W, 0}, {-W, W, 0});
    addQuad(s, {0, -W, h}, {0, W, h}, {W, W, h}, {W, -W, h});
    return s;
}

// Composite 8-point Gauss-Legendre on [lo, hi] in `panels` panels: (node, weight) pairs.
// The integrands below are analytic, and 16 panels take them to rounding.
std::vector<std::pair<double, double>> gaussLegendre(double lo, double hi, int panels = 16) {
    const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                         0.9602898564975363};
    const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                         0.1012285362903763};
    std::vector<std::pair<double, double>> r;
    const double width = (hi - lo) / panels;
    for (int p = 0; p < panels; ++p) {
        const double mid = lo + (p + 0.5) * width;
        for (int i = 0; i < 4; ++i) {
            r.push_back({mid + 0.5 * width * x[i], 0.5 * width * w[i]});
            r.push_back({mid - 0.5 * width * x[i], 0.5 * width * w[i]});
        }
    }
    return r;
}

// The integral of Y_k(w) (n.w) over the lune {w.a > 0, w.b > 0} (a, b unit and not
// parallel, n.w >= 0 there). With a = n = z it is the part of an upward normal's sky that
// the overhang hides. About the axis u = a x b the lune is the wedge of azimuths
// (beta - pi/2, pi/2) at every polar angle theta, where b = cos(beta) a + sin(beta) e2: a
// product domain, integrated by Gauss-Legendre in theta (dw = sin(theta) dtheta dphi) and
// in phi. Written without sky_transfer.cpp's sampling.
Sh9 luneIntegral(const Vec3& a, const Vec3& b, const Vec3& n) {
    const Vec3 u = glm::normalize(glm::cross(a, b));
    const Vec3 e2 = glm::cross(u, a);
    const double beta = std::atan2(glm::dot(b, e2), glm::dot(b, a));
    Sh9 T{};
    for (const auto& [phi, wp] : gaussLegendre(beta - kPi / 2, kPi / 2)) {
        for (const auto& [theta, wt] : gaussLegendre(0, kPi)) {
            const double s = std::sin(theta);
            const Vec3 w = std::cos(theta) * u + s * (std::cos(phi) * a + std::sin(phi) * e2);
            const Sh9 y = sh9Basis(w);
            for (int k = 0; k < kSh9Count; ++k) T[k] += y[k] * glm::dot(n, w) * s * wt * wp;
        }
    }
    return T;
}

// The part of an upward normal's sky an overhang hides, the half-space w.b > 0 above.
Sh9 hiddenByOverhang(const Vec3& b) {
    const Vec3 z{0, 0, 1};
    return luneIntegral(z, b, z);
}

// The stratified estimate's error, measured with 64 seeds on the unoccluded normals and
// the overhang points of the tests below: with 256 / 1024 / 4096 rays its rms is 6.2e-3 /
// 1.5e-3 / 4.1e-4 unoccluded (1 / N: the Y_k are smooth over the strata) and 6.8e-3 /
// 2.4e-3 / 8.8e-4 under the overhang (about 1 / N^0.75: its edge cuts strata); the largest
// errors at 4096 rays were 1.8e-3 and 5.0e-3. The tolerances are twice those; a wrong A_l,
// or a blocker missed, is off by 0.1 or more.
constexpr int kRays = 4096;
constexpr double kOpenTol = 3.5e-3;
constexpr double kEdgeTol = 1e-2;

TEST(SkyTransfer, UnoccludedIsTheCosineTransfer) {
    const Scene empty;
    const Visibility vis(empty);
    for (const Vec3 n : {Vec3{0, 0, 1}, Vec3{0, -3, 0}, Vec3{1, -2, 0.5}}) {
        const Sh9 T = skyTransfer(vis, empty.bounds(), {{1, 2, 3}, n}, 0, {kRays});
        const Sh9 ref = sh9CosineTransfer(glm::normalize(n));
        EXPECT_NEAR(T[0], ref[0], 1e-12);  // Y_0 is constant: every ray weighs the same
        for (int k = 1; k < kSh9Count; ++k) EXPECT_NEAR(T[k], ref[k], kOpenTol) << "k " << k;
    }
}

TEST(SkyTransfer, OwnPolygonDoesNotOcclude) {
    // A point on the ground, its polygon given: nothing above it, the whole upper sky.
    Scene s = overhangScene(1, 1e4);
    s.polygons.pop_back();  // the overhang
    const Visibility vis(s);
    const Sh9 T = skyTransfer(vis, s.bounds(), {{-5, 0, 0}, {0, 0, 1}, 0}, 0, {kRays});
    const Sh9 ref = sh9CosineTransfer({0, 0, 1});
    for (int k = 0; k < kSh9Count; ++k) EXPECT_NEAR(T[k], ref[k], kOpenTol) << "k " << k;
}

TEST(SkyTransfer, UnderTheOverhangsEdgeHalfTheSkyIsHidden) {
    // Right under the edge (x = 0) the overhang hides exactly the quarter sphere
    // {z > 0, x > 0}; integrating Y_k(w) w_z over the other quarter in closed form:
    //   T00 = c0 pi/2, T10 = c1 pi/3, T11 = -2 c1/3, T20 = c20 pi/4, T21 = -c2 pi/8,
    // the others 0 (odd in y, or cos(2 phi) over a half turn).
    const double c0 = 0.5 / std::sqrt(kPi), c1 = std::sqrt(3 / (4 * kPi));
    const double c2 = 0.5 * std::sqrt(15 / kPi), c20 = 0.25 * std::sqrt(5 / kPi);
    const Sh9 analytic{c0 * kPi / 2,  0, c1 * kPi / 3, -2 * c1 / 3, 0, 0, c20 * kPi / 4,
                       -c2 * kPi / 8, 0};
    // The reference integrator agrees with the closed form (1e-12: rounding).
    const Sh9 open = sh9CosineTransfer({0, 0, 1}), hidden = hiddenByOverhang({1, 0, 0});
    for (int k = 0; k < kSh9Count; ++k) EXPECT_NEAR(open[k] - hidden[k], analytic[k], 1e-12);

    const Scene s = overhangScene(1, 1e4);
    const Visibility vis(s);
    const Sh9 T = skyTransfer(vis, s.bounds(), {{0, 0.3, 0}, {0, 0, 1}, 0}, 0, {kRays});
    for (int k = 0; k < kSh9Count; ++k) EXPECT_NEAR(T[k], analytic[k], kEdgeTol) << "k " << k;
}

TEST(SkyTransfer, AwayFromTheEdgeTheHiddenLuneMatchesItsIntegral) {
    // At (x0, 0, 0) under an overhang at height h over x > 0, the ray along w (w_z > 0)
    // meets the overhang where x0 + h w_x / w_z > 0: the half-space w.(h, 0, x0) > 0. The
    // hidden part of the sky is the lune between it and the horizon.
    const double h = 2;
    const Scene s = overhangScene(h, 2e4);
    const Visibility vis(s);
    for (const double x0 : {-1.5, -0.4, 0.7, 3.0}) {
        const Sh9 open = sh9CosineTransfer({0, 0, 1});
        const Sh9 hidden = hiddenByOverhang(glm::normalize(Vec3{h, 0, x0}));
        const Sh9 T = skyTransfer(vis, s.bounds(), {{x0, -0.2, 0}, {0, 0, 1}, 0}, 7, {kRays});
        for (int k = 0; k < kSh9Count; ++k)
            EXPECT_NEAR(T[k], open[k] - hidden[k], kEdgeTol) << "x0 " << x0 << " k " << k;
    }
}

TEST(SkyTransfer, AWallsFootSeesTheUpperHalfOfItsHemisphere) {
    // A point on a wall facing +x, 0.5 m above the ground: the ground hides every
    // direction below the horizon, so T is the integral of Y_k(w) w_x over
    // {w_x > 0, w_z > 0}. The wall is the point's own polygon; the ground blocks.
    const double W = 1e4;
    Scene s;
    s.objects.push_back("yard");
    addQuad(s, {-W, -W, 0}, {W, -W, 0}, {W, W, 0}, {-W, W, 0});  // ground, up
    addQuad(s, {0, -W, 0}, {0, W, 0}, {0, W, W}, {0, -W, W});    // wall, facing +x
    const Visibility vis(s);
    const Vec3 x{1, 0, 0};
    const Sh9 ref = luneIntegral(x, {0, 0, 1}, x);
    const Sh9 T = skyTransfer(vis, s.bounds(), {{0, 0.3, 0.5}, x, 1}, 3, {kRays});
    for (int k = 0; k < kSh9Count; ++k) EXPECT_NEAR(T[k], ref[k], kEdgeTol) << "k " << k;
    // Half the cosine-weighted hemisphere: T00 = c0 pi / 2.
    EXPECT_NEAR(ref[0], 0.5 / std::sqrt(kPi) * kPi / 2, 1e-12);
}

TEST(SkyTransfer, OccludedIrradianceIsTheDotProduct) {
    // A uniform sky of radiance 1 (L00 = 1 / c0): the irradiance of a point that sees a
    // fraction f of its cosine-weighted sky is pi f; under the overhang's edge f = 1/2.
    const Scene s = overhangScene(1, 1e4);
    const Visibility vis(s);
    Sh9Rgb uniform;
    uniform.c[0] = Rgb::gray(2 * std::sqrt(kPi));
    const Sh9 T = skyTransfer(vis, s.bounds(), {{0, 0, 0}, {0, 0, 1}, 0}, 0, {kRays});
    // T00 is within kEdgeTol, so E within L00 kEdgeTol = 0.016.
    EXPECT_NEAR(sh9Dot(T, uniform).g, kPi / 2, 2 * std::sqrt(kPi) * kEdgeTol);
    // The sky's first coefficient alone: T00 L00 = pi (rays seen / rays), exactly.
    EXPECT_NEAR(sh9Dot(T, uniform).g, 2 * std::sqrt(kPi) * T[0], 1e-12);
}

TEST(SkyTransfer, ManyPointsAreTheSingleOnesWhateverTheThreads) {
    const Scene s = overhangScene(1, 100);
    const Visibility vis(s);
    std::vector<SkyPoint> points;
    for (int i = 0; i < 40; ++i) points.push_back({{0.1 * i - 2, 0.05 * i, 0}, {0, 0, 1}, 0});
    points.push_back({{0.5, 0, 0.5}, {1, 0, 1}});  // in the air, tilted, on no polygon
    const SkyTransferOptions options{64, 99};
    const std::vector<Sh9> T = skyTransfers(vis, s.bounds(), points, options);
    ASSERT_EQ(T.size(), points.size());
    for (size_t i = 0; i < points.size(); ++i)
        EXPECT_EQ(T[i], skyTransfer(vis, s.bounds(), points[i], i, options)) << i;
    EXPECT_TRUE(skyTransfers(vis, s.bounds(), {}, options).empty());
}

TEST(SkyTransfer, RefusesZeroNormalsAndNoRays) {
    const Scene empty;
    const Visibility vis(empty);
    EXPECT_THROW(skyTransfer(vis, empty.bounds(), {{0, 0, 0}, {0, 0, 0}}, 0),
                 std::invalid_argument);
    EXPECT_THROW(skyTransfer(vis, empty.bounds(), {{0, 0, 0}, {0, NAN, 1}}, 0),
                 std::invalid_argument);
    EXPECT_THROW(skyTransfer(vis, empty.bounds(), {{0, 0, 0}, {0, 0, 1}}, 0, {0}),
                 std::invalid_argument);
    const std::vector<SkyPoint> points{{{0, 0, 0}, {0, 0, 1}}, {{0, 0, 0}, {0, 0, 1e-13}}};
    try {
        skyTransfers(vis, empty.bounds(), points);
        FAIL() << "a zero normal was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace radiosity
