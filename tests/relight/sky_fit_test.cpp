// Sky fit (relight/pipeline/sky_fit.h): images rendered here from known skies (and suns)
// give them back, exactly without noise and within the least-squares bound with it; pixels
// that face one way are refused, or regularised when asked; bad input is refused; a fit held
// to a sky that is not negative anywhere is the least squares where that already holds, and
// no farther from a true sky than the least squares where it does not.
#include "relight/pipeline/sky_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "radiosity/sky_transfer.h"
#include "tests/support/skies.h"

namespace relight {
namespace {

using radiosity::Rgb;
using radiosity::Sh9;
using radiosity::Sh9Rgb;
using radiosity::Vec3;
constexpr double kPi = std::numbers::pi;

using radiosity::test::clearSky;  // tests/support/skies.h

// The radiance of the model, I = (rho / pi) (T.L + f s): how the test renders its image.
Rgb render(const SkyFitPixel& px, const Sh9Rgb& L, const Rgb& sun) {
    return px.reflectance * (radiosity::sh9Dot(px.transfer, L) + sun * px.sunFactor) * (1 / kPi);
}

// Pixels facing every way, with occlusion: each sees a random share of its sky, as a
// transfer vector damped per band (what a blocker does to T, crudely), so that the T_p
// are not those of an open sky; random reflectances; the sun along `sunDir`, hidden from
// a third of them.
std::vector<SkyFitPixel> pixels(int n, uint32_t seed, const Vec3& sunDir) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<SkyFitPixel> out;
    for (int i = 0; i < n; ++i) {
        const Vec3 normal = glm::normalize(Vec3{g(rng), g(rng), g(rng)});
        SkyFitPixel px;
        px.transfer = radiosity::sh9CosineTransfer(normal);
        const double open = 0.4 + 0.6 * u(rng), damp = 0.5 + 0.5 * u(rng);
        for (int k = 0; k < radiosity::kSh9Count; ++k)
            px.transfer[static_cast<size_t>(k)] *= open * (radiosity::sh9Band(k) == 2 ? damp : 1);
        px.reflectance = {0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng)};
        px.sunFactor = u(rng) < 1.0 / 3 ? 0.0 : std::max(0.0, glm::dot(normal, sunDir));
        out.push_back(px);
    }
    return out;
}

void expectSkyNear(const Sh9Rgb& a, const Sh9Rgb& b, double tol) {
    for (int k = 0; k < radiosity::kSh9Count; ++k)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(a.c[static_cast<size_t>(k)][c], b.c[static_cast<size_t>(k)][c], tol)
                << "k " << k << " channel " << c;
}

const Vec3 kSunDir = glm::normalize(Vec3{0.4, -0.3, 0.8});

TEST(SkyFit, NoiselessImageGivesTheSkyBack) {
    // Exact data and a well-conditioned system (normals everywhere): only rounding is left,
    // amplified by the scaled system's condition number (~10^2 here) squared by the normal
    // equations: the largest error measured is 5e-12; 1e-9 is far above it and far below
    // any fault.
    std::vector<SkyFitPixel> px = pixels(2000, 1, kSunDir);
    const Sh9Rgb L = clearSky();
    for (SkyFitPixel& p : px) p.radiance = render(p, L, {});
    const SkyFitResult fit = fitSky(px);
    EXPECT_EQ(fit.unknowns, 9);
    EXPECT_EQ(fit.rank, 9);
    EXPECT_FALSE(fit.regularised);
    expectSkyNear(fit.sky, L, 1e-9);
    EXPECT_LT(fit.rmsResidual.maxComponent(), 1e-12);
    EXPECT_EQ(fit.sunIrradiance, Rgb{});
}

TEST(SkyFit, JointFitGivesSkyAndSunBack) {
    std::vector<SkyFitPixel> px = pixels(2000, 2, kSunDir);
    const Sh9Rgb L = clearSky();
    const Rgb sun{3.0, 2.8, 2.4};
    for (SkyFitPixel& p : px) p.radiance = render(p, L, sun);
    const SkyFitResult fit = fitSky(px, {.fitSun = true});
    EXPECT_EQ(fit.unknowns, 10);
    EXPECT_EQ(fit.rank, 10);
    expectSkyNear(fit.sky, L, 1e-9);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fit.sunIrradiance[c], sun[c], 1e-9);
    // Without the sun term the same image is fitted worse: the sun is not a sky of order 2.
    const SkyFitResult skyOnly = fitSky(px);
    EXPECT_GT(skyOnly.rmsResidual.minComponent(), 1e-3);
}

TEST(SkyFit, NoisyImageStaysWithinTheLeastSquaresBound) {
    // Gaussian noise of sigma on every pixel: the least-squares estimate is unbiased with
    // covariance sigma^2 (A^T A)^-1 (Gauss-Markov), computed here from the design matrix
    // independently of sky_fit.cpp. Every coefficient must lie within 5 standard deviations
    // (a chance of 6e-7 each, 3e-5 for the 30 of them).
    const double sigma = 0.01;
    std::vector<SkyFitPixel> px = pixels(3000, 3, kSunDir);
    const Sh9Rgb L = clearSky();
    const Rgb sun{3.0, 2.8, 2.4};
    std::mt19937 rng(17);
    std::normal_distribution<double> noise(0, sigma);
    for (SkyFitPixel& p : px)
        p.radiance = render(p, L, sun) + Rgb{noise(rng), noise(rng), noise(rng)};
    const SkyFitResult fit = fitSky(px, {.fitSun = true});
    for (int c = 0; c < 3; ++c) {
        Eigen::MatrixXd A(static_cast<Eigen::Index>(px.size()), 10);
        for (size_t p = 0; p < px.size(); ++p) {
            const auto row = static_cast<Eigen::Index>(p);
            for (int k = 0; k < 9; ++k)
                A(row, k) = px[p].reflectance[c] / kPi * px[p].transfer[static_cast<size_t>(k)];
            A(row, 9) = px[p].reflectance[c] / kPi * px[p].sunFactor;
        }
        const Eigen::MatrixXd cov = sigma * sigma * (A.transpose() * A).inverse();
        for (int k = 0; k < 9; ++k) {
            const double sd = std::sqrt(cov(k, k));
            EXPECT_NEAR(fit.sky.c[static_cast<size_t>(k)][c], L.c[static_cast<size_t>(k)][c],
                        5 * sd)
                << "k " << k << " channel " << c << " sd " << sd;
        }
        EXPECT_NEAR(fit.sunIrradiance[c], sun[c], 5 * std::sqrt(cov(9, 9)));
        // The residual is the noise: sqrt((P - 10) / P) sigma, within a few percent.
        EXPECT_NEAR(fit.rmsResidual[c], sigma, 0.05 * sigma);
    }
}

TEST(SkyFit, PixelsFacingOneWayAreRefusedOrRegularised) {
    // A wall facing +x, unoccluded: every pixel has T = A_l Y_k(+x) and sees one number,
    // E(+x). The nine coefficients are undetermined (rank 1).
    std::vector<SkyFitPixel> px(500);
    const Sh9Rgb L = clearSky();
    const Vec3 n{1, 0, 0};
    for (size_t i = 0; i < px.size(); ++i) {
        px[i].transfer = radiosity::sh9CosineTransfer(n);
        px[i].reflectance = Rgb::gray(0.2 + 0.001 * static_cast<double>(i));
        px[i].radiance = render(px[i], L, {});
    }
    try {
        fitSky(px);
        FAIL() << "a rank-deficient fit was accepted";
    } catch (const SkyFitError& e) {
        EXPECT_NE(std::string(e.what()).find("determine only 1 of the 9"), std::string::npos)
            << e.what();
    }
    // With a ridge: flagged, and the one thing the pixels say, E(+x), is kept (to the
    // ridge's relative bias, 1e-8 here), while the sky need not be the one rendered.
    const SkyFitResult fit = fitSky(px, {.ridge = 1e-8});
    EXPECT_TRUE(fit.regularised);
    EXPECT_EQ(fit.rank, 1);
    const Rgb E = radiosity::sh9Irradiance(L, n), Efit = radiosity::sh9Irradiance(fit.sky, n);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(Efit[c], E[c], 1e-6 * E[c]);
    EXPECT_LT(fit.rmsResidual.maxComponent(), 1e-6);
}

// The sky's radiance at n directions of a Fibonacci sphere, its lowest over the channels.
double lowestRadiance(const Sh9Rgb& L, int n) {
    double lowest = 1e300;
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z);
        const Rgb v =
            radiosity::sh9Eval(L, {r * std::cos(golden * i), r * std::sin(golden * i), z});
        lowest = std::min({lowest, v.r, v.g, v.b});
    }
    return lowest;
}

TEST(SkyFit, HoldingTheSkyNonNegativeChangesNothingWhereItAlreadyIs) {
    // Pixels facing every way, noiseless: the least squares is the true sky, whose radiance
    // is positive everywhere, so no constraint is active and the fit is the same.
    std::vector<SkyFitPixel> px = pixels(2000, 8, kSunDir);
    const Rgb sun{3.0, 2.8, 2.4};
    for (SkyFitPixel& p : px) p.radiance = render(p, clearSky(), sun);
    ASSERT_GT(lowestRadiance(clearSky(), 4000), 0.0);
    const SkyFitResult plain = fitSky(px, {.fitSun = true});
    const SkyFitResult held = fitSky(px, {.fitSun = true, .nonNegative = true});
    EXPECT_EQ(held.activeConstraints, 0);
    expectSkyNear(held.sky, plain.sky, 1e-12);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(held.sunIrradiance[c], plain.sunIrradiance[c]);
}

// Pixels of a courtyard seen from above: the ground (normals within 20 degrees of +z) and
// three walls (+x, +y, -x), each pixel seeing a random share of its sky, noise of sigma.
std::vector<SkyFitPixel> courtyardPixels(int n, double sigma, const Sh9Rgb& L, const Rgb& sun) {
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> noise(0, sigma);
    const Vec3 walls[3] = {{1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
    std::vector<SkyFitPixel> out;
    for (int i = 0; i < n; ++i) {
        Vec3 normal = walls[i % 3];
        if (i % 2 == 0)
            normal = glm::normalize(Vec3{0.35 * (u(rng) - 0.5), 0.35 * (u(rng) - 0.5), 1});
        SkyFitPixel px;
        px.transfer = radiosity::sh9CosineTransfer(normal);
        const double open = 0.5 + 0.5 * u(rng);
        for (double& t : px.transfer) t *= open;
        px.reflectance = Rgb{0.3, 0.28, 0.25} * (0.8 + 0.4 * u(rng));
        px.sunFactor = std::max(0.0, glm::dot(normal, kSunDir));
        px.radiance = render(px, L, sun) + Rgb{noise(rng), noise(rng), noise(rng)};
        out.push_back(px);
    }
    return out;
}

TEST(SkyFit, ANonNegativeSkyIsNoFartherFromATrueSkyThanTheLeastSquares) {
    // With the pixels' few directions, the regularised least squares x^ sets the
    // undetermined coefficients from noise, and its sky goes negative. The fit held to
    // G x >= 0 minimises the same quadratic, ||x - x^||_Q^2 plus a constant, over a convex
    // set that holds the true sky x* (positive everywhere): it is the Q-projection of x^ on
    // that set, and a projection onto a convex set is no farther from any of its points,
    // ||x_c - x*||_Q <= ||x^ - x*||_Q. Q is the normal matrix with its ridge, computed here
    // from the pixels, independently of sky_fit.cpp. Slack: 1e-6 relative, for the dual's
    // iterations (they stop at a move of 1e-12 of the solution's Q-norm).
    const Sh9Rgb L = clearSky();
    const Rgb sun{3.0, 2.8, 2.4};
    const std::vector<SkyFitPixel> px = courtyardPixels(3000, 0.05, L, sun);
    const SkyFitOptions plainOptions{.fitSun = true, .ridge = 1e-3, .rankTolerance = 1e-4};
    SkyFitOptions heldOptions = plainOptions;
    heldOptions.nonNegative = true;
    const SkyFitResult plain = fitSky(px, plainOptions), held = fitSky(px, heldOptions);
    ASSERT_TRUE(plain.regularised);  // the pixels leave some directions undetermined
    EXPECT_LT(lowestRadiance(plain.sky, kNonNegativeDirections), 0.0);  // the case at issue
    EXPECT_GT(held.activeConstraints, 0);
    // Held at the constraint's directions, to the dual's tolerance.
    EXPECT_GE(lowestRadiance(held.sky, kNonNegativeDirections), -1e-9);
    for (int c = 0; c < 3; ++c) {
        Eigen::MatrixXd N = Eigen::MatrixXd::Zero(10, 10);
        for (const SkyFitPixel& p : px) {
            Eigen::VectorXd a(10);
            for (int k = 0; k < 9; ++k)
                a[k] = p.reflectance[c] / kPi * p.transfer[static_cast<size_t>(k)];
            a[9] = p.reflectance[c] / kPi * p.sunFactor;
            N += a * a.transpose();
        }
        // The ridge is relative to the unit-scaled diagonal: ridge * diag(N) unscaled.
        const Eigen::MatrixXd Q =
            N + Eigen::MatrixXd(plainOptions.ridge * N.diagonal().asDiagonal());
        auto distance = [&](const SkyFitResult& f) {
            Eigen::VectorXd d(10);
            for (int k = 0; k < 9; ++k)
                d[k] = f.sky.c[static_cast<size_t>(k)][c] - L.c[static_cast<size_t>(k)][c];
            d[9] = f.sunIrradiance[c] - sun[c];
            return std::sqrt(d.dot(Q * d));
        };
        EXPECT_LE(distance(held), distance(plain) * (1 + 1e-6)) << "channel " << c;
    }
}

TEST(SkyFit, ASunThatNoPixelSeesIsRefused) {
    std::vector<SkyFitPixel> px = pixels(500, 4, kSunDir);
    for (SkyFitPixel& p : px) {
        p.sunFactor = 0;
        p.radiance = render(p, clearSky(), {});
    }
    EXPECT_THROW(fitSky(px, {.fitSun = true}), SkyFitError);
    EXPECT_NO_THROW(fitSky(px));
}

TEST(SkyFit, FewerPixelsThanUnknownsAreRefused) {
    std::vector<SkyFitPixel> px = pixels(8, 5, kSunDir);
    for (SkyFitPixel& p : px) p.radiance = render(p, clearSky(), {});
    EXPECT_THROW(fitSky(px), SkyFitError);
}

TEST(SkyFit, RefusesNoPixelsAndValuesThatAreNotFinite) {
    EXPECT_THROW(fitSky({}), std::invalid_argument);
    std::vector<SkyFitPixel> px = pixels(50, 6, kSunDir);
    for (SkyFitPixel& p : px) p.radiance = render(p, clearSky(), {});
    EXPECT_THROW(fitSky(px, {.ridge = -1}), std::invalid_argument);
    px[7].transfer[3] = NAN;
    try {
        fitSky(px);
        FAIL() << "a NaN was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("pixel 7"), std::string::npos) << e.what();
    }
}

TEST(SkyFit, FitsARenderedCourtyardThroughItsRayCastTransfers) {
    // The whole chain: transfer vectors cast in a courtyard (ground, two walls and an
    // overhang), an image rendered from them and a sky and sun, the fit. The same T render
    // and fit, so the sky comes back to rounding, if the occlusion makes the system
    // determined: the walls' and the ground's normals alone give 3 numbers, the occlusion's
    // variation over them the rest.
    radiosity::Scene s;
    s.objects.push_back("courtyard");
    auto quad = [&s](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
        s.polygons.push_back(radiosity::makePolygon({a, b, c, d}, 0, Rgb::gray(0.5)));
    };
    quad({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0});      // ground, up
    quad({0, 0, 0}, {0, 4, 0}, {0, 4, 3}, {0, 0, 3});      // wall x = 0, facing +x
    quad({0, 0, 0}, {0, 0, 3}, {4, 0, 3}, {4, 0, 0});      // wall y = 0, facing +y
    quad({0, 0, 2}, {0, 2, 2}, {1.5, 2, 2}, {1.5, 0, 2});  // overhang, facing down
    const radiosity::Visibility vis(s);
    std::vector<radiosity::SkyPoint> points;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
            const double a = 0.25 + 0.45 * i, b = 0.25 + 0.45 * j;
            points.push_back({{a, b, 0}, {0, 0, 1}, 0});
            points.push_back({{0, a, 0.35 * b}, {1, 0, 0}, 1});
            points.push_back({{a, 0, 0.35 * b}, {0, 1, 0}, 2});
        }
    const std::vector<Sh9> T = radiosity::skyTransfers(vis, s.bounds(), points, {.rays = 64});
    std::vector<SkyFitPixel> px(points.size());
    for (size_t i = 0; i < px.size(); ++i) {
        px[i].transfer = T[i];
        px[i].reflectance = Rgb{0.5, 0.45, 0.4};
        px[i].radiance = render(px[i], clearSky(), {});
    }
    const SkyFitResult fit = fitSky(px);
    EXPECT_EQ(fit.rank, 9);
    expectSkyNear(fit.sky, clearSky(), 1e-9);  // 5e-12 measured
}

}  // namespace
}  // namespace relight
