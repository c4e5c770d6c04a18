// Sky fit (relight/pipeline/sky_fit.h): images rendered here from known skies (and suns)
// give them back, exactly without noise and within the least-squares bound with it; pixels
// that face one way are refused, or regularised when asked; bad input is refused.
#include "relight/pipeline/sky_fit.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
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
