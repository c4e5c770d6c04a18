// Sh9 (radiosity/sh9.h): the basis against the format's constants, projection, irradiance
// against Ramamoorthi & Hanrahan's published Grace Cathedral figures and their matrix form,
// and rotations (pointwise, inverse, composition, invariants, the right-hand sense).
#include "radiosity/sh9.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace radiosity {
namespace {

constexpr double kPi = std::numbers::pi;

// n directions spread evenly over the sphere (a Fibonacci lattice).
std::vector<Vec3> sphereDirections(int n) {
    std::vector<Vec3> d;
    const double golden = kPi * (3 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
        d.push_back({r * std::cos(golden * i), r * std::sin(golden * i), z});
    }
    return d;
}

Sh9Rgb randomSky(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    Sh9Rgb L;
    for (Rgb& c : L.c) c = {u(rng), u(rng), u(rng)};
    return L;
}

// Ramamoorthi & Hanrahan 2001, Fig. 2: the Grace Cathedral's coefficients as printed.
Sh9Rgb graceCathedral() {
    Sh9Rgb L;
    L.c = {Rgb{.79, .44, .54},    Rgb{.39, .35, .60},    Rgb{-.34, -.18, -.27},
           Rgb{-.29, -.06, .01},  Rgb{-.11, -.05, -.12}, Rgb{-.26, -.22, -.47},
           Rgb{-.16, -.09, -.15}, Rgb{.56, .21, .14},    Rgb{.21, -.05, -.30}};
    return L;
}

void expectRgbNear(const Rgb& a, const Rgb& b, double tol) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tol) << "channel " << c;
}

TEST(Sh9, BasisMatchesTheFormatsPrintedConstants) {
    // docs/scene-format.md prints the constants to 6 digits: 5e-7 is half their last digit,
    // times the largest |polynomial| (3 for 3z^2 - 1) for Y20.
    for (const Vec3& w : sphereDirections(50)) {
        const double x = w.x, y = w.y, z = w.z;
        const double printed[9] = {0.282095,
                                   0.488603 * y,
                                   0.488603 * z,
                                   0.488603 * x,
                                   1.092548 * x * y,
                                   1.092548 * y * z,
                                   0.315392 * (3 * z * z - 1),
                                   1.092548 * x * z,
                                   0.546274 * (x * x - y * y)};
        const Sh9 Y = sh9Basis(w);
        for (int k = 0; k < kSh9Count; ++k) EXPECT_NEAR(Y[k], printed[k], 1.5e-6) << "k " << k;
    }
}

TEST(Sh9, BasisIsOrthonormal) {
    // The product rule is exact for polynomials of degree <= 2 zNodes - 3 (sh9.h); Y_j Y_k
    // has degree 4, so 3 nodes suffice, and 12 must give the same: rounding only.
    for (const int nodes : {3, 12}) {
        for (int j = 0; j < kSh9Count; ++j) {
            const Sh9 p = sh9Project([j](const Vec3& w) { return sh9Basis(w)[j]; }, nodes);
            for (int k = 0; k < kSh9Count; ++k)
                EXPECT_NEAR(p[k], j == k ? 1.0 : 0.0, 1e-13) << "j " << j << " k " << k;
        }
    }
}

TEST(Sh9, ProjectionOfABandLimitedSkyGivesItsCoefficients) {
    const Sh9Rgb L = randomSky(3);
    const Sh9Rgb p = sh9ProjectRgb([&L](const Vec3& w) { return sh9Eval(L, w); }, 4);
    for (int k = 0; k < kSh9Count; ++k) expectRgbNear(p.c[k], L.c[k], 1e-13);
    // A band-3 term (xyz, orthogonal to bands 0-2) adds nothing to the nine.
    const Sh9Rgb q = sh9ProjectRgb(
        [&L](const Vec3& w) { return sh9Eval(L, w) + Rgb::gray(5 * w.x * w.y * w.z); }, 4);
    for (int k = 0; k < kSh9Count; ++k) expectRgbNear(q.c[k], L.c[k], 1e-13);
    EXPECT_THROW(sh9Project([](const Vec3&) { return 1.0; }, 0), std::invalid_argument);
}

TEST(Sh9, ProjectedClampedCosineIsTheCosineTransfer) {
    // R&H 2001, Eqs. 5-7: the clamped cosine max(0, n.w) has coefficients A_l Y_k(n). For
    // n = +z these are Google's spherical-harmonics cosine_lobe (0.886227, 1.02333,
    // 0.495416). The kink at the horizon makes the product rule converge only as 1/N^2:
    // the largest error over these normals measured 3.2e-4, 8.1e-5 and 2.0e-5 with 50, 100
    // and 200 nodes; 1e-4 leaves five times that, and a wrong A_l (pi/2 for band 1, say)
    // is off by 0.25.
    const Sh9 zt = sh9CosineTransfer({0, 0, 1});
    EXPECT_NEAR(zt[0], 0.886227, 1e-6);
    EXPECT_NEAR(zt[2], 1.02333, 1e-5);
    EXPECT_NEAR(zt[6], 0.495416, 1e-6);
    for (const Vec3 n : {Vec3{0, 0, 1}, glm::normalize(Vec3{1, -2, 0.5}), Vec3{0, -1, 0}}) {
        const Sh9 p =
            sh9Project([&n](const Vec3& w) { return std::max(0.0, glm::dot(n, w)); }, 200);
        const Sh9 t = sh9CosineTransfer(n);
        for (int k = 0; k < kSh9Count; ++k) EXPECT_NEAR(p[k], t[k], 1e-4) << "k " << k;
    }
}

TEST(Sh9, GraceCathedralIrradianceMatchesThePublishedFigures) {
    // The E(+z) and E(-y) for R&H 2001 Fig. 2's coefficients taken as printed.
    // They are E itself (irradiance, A_0 = pi, no division by pi): R&H's Eq. 13 with their
    // c1..c5 gives 0.272921, 0.161153, 0.127951 at +z; E/pi would be 0.0869 at +z. Printed
    // to 5 decimals: 5e-6 is half the last digit, plus 1e-6 for the basis' rounding.
    const Sh9Rgb L = graceCathedral();
    expectRgbNear(sh9Irradiance(L, {0, 0, 1}), {0.27292, 0.16115, 0.12795}, 6e-6);
    expectRgbNear(sh9Irradiance(L, {0, -1, 0}), {0.25056, 0.07552, 0.03044}, 6e-6);
}

TEST(Sh9, IrradianceMatrixIsRamamoorthiHanrahanEq12) {
    // R&H 2001 print c1..c5 (Eq. 12) to 6 digits, computed from the 6-digit basis
    // constants (their c3 = 3 (pi/4) 0.315392 = 0.7431246, 1.1e-6 from the exact value):
    // 1.5e-6 covers both roundings. Read them back from M of unit channels.
    Sh9 e{};
    e[8] = 1;
    EXPECT_NEAR(sh9IrradianceMatrix(e)[0][0], 0.429043, 1.5e-6);  // c1 L22
    e = {};
    e[1] = 1;
    EXPECT_NEAR(sh9IrradianceMatrix(e)[3][1], 0.511664, 1.5e-6);  // c2 L1-1
    e = {};
    e[6] = 1;
    EXPECT_NEAR(sh9IrradianceMatrix(e)[2][2], 0.743125, 1.5e-6);   // c3 L20
    EXPECT_NEAR(sh9IrradianceMatrix(e)[3][3], -0.247708, 1.5e-6);  // -c5 L20
    e = {};
    e[0] = 1;
    EXPECT_NEAR(sh9IrradianceMatrix(e)[3][3], 0.886227, 1.5e-6);  // c4 L00
    // n^T M n (Eq. 11) equals sum_k A_l L_k Y_k(n) (Eq. 7) for every normal and channel.
    const Sh9Rgb sky = graceCathedral();
    for (int ch = 0; ch < 3; ++ch) {
        const glm::dmat4 M = sh9IrradianceMatrix(sky.channel(ch));
        for (const Vec3& n : sphereDirections(200))
            EXPECT_NEAR(sh9IrradianceQuadratic(M, n), sh9Irradiance(sky, n)[ch], 1e-14);
    }
}

TEST(Sh9, IrradianceIsTheCosineIntegralOfTheRadiance) {
    // Independent of the A_l: integrate L(w) max(0, n.w) numerically (1/N^2 as above).
    const Sh9Rgb L = graceCathedral();
    for (const Vec3 n : {glm::normalize(Vec3{0.3, 0.4, -1}), Vec3{1, 0, 0}}) {
        const Sh9Rgb p = sh9ProjectRgb(
            [&](const Vec3& w) { return sh9Eval(L, w) * std::max(0.0, glm::dot(n, w)); }, 200);
        // The integral is the first coefficient over Y00 = 1 / (2 sqrt(pi)).
        expectRgbNear(p.c[0] * (2 * std::sqrt(kPi)), sh9Irradiance(L, n), 2e-4);
    }
}

TEST(Sh9, RotationAboutAxisIsRodrigues) {
    // A quarter turn about +z takes +x to +y (right-hand rule).
    const glm::dmat3 R = rotationAboutAxis({0, 0, 2}, 90);
    const Vec3 x = R * Vec3{1, 0, 0};
    EXPECT_NEAR(glm::length(x - Vec3{0, 1, 0}), 0.0, 1e-15);
    const Vec3 axis = glm::normalize(Vec3{1, 2, -0.5});
    const glm::dmat3 Q = rotationAboutAxis(axis, 37);
    EXPECT_NEAR(glm::length(Q * axis - axis), 0.0, 1e-15);
    const glm::dmat3 I = glm::transpose(Q) * Q;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) EXPECT_NEAR(I[i][j], i == j ? 1.0 : 0.0, 1e-15);
    EXPECT_NEAR(glm::determinant(Q), 1.0, 1e-15);
    // No axis, no rotation.
    EXPECT_THROW(rotationAboutAxis({0, 0, 0}, 90), std::invalid_argument);
    EXPECT_THROW(rotationAboutAxis({1e-13, 0, 0}, 90), std::invalid_argument);
    EXPECT_THROW(rotationAboutAxis({std::nan(""), 0, 1}, 90), std::invalid_argument);
    EXPECT_THROW(rotationAboutAxis({0, 0, 1}, INFINITY), std::invalid_argument);
}

TEST(Sh9, QuarterTurnAboutZIsTheSkyEvaluatedAtTheTurnedDirection) {
    // R_z(90) maps (x, y, z) to (-y, x, z), so R^T w = (y, -x, z): written out here rather
    // than taken from rotationAboutAxis.
    const Sh9Rgb L = randomSky(11);
    const Sh9Rgb turned = sh9RotateAboutAxis(L, {0, 0, 1}, 90);
    for (const Vec3& w : sphereDirections(500))
        expectRgbNear(sh9Eval(turned, w), sh9Eval(L, {w.y, -w.x, w.z}), 1e-13);
}

TEST(Sh9, AnyRotationIsTheSkyEvaluatedAtTheTurnedDirection) {
    const Sh9Rgb L = randomSky(5);
    std::mt19937 rng(9);
    std::normal_distribution<double> g;
    std::uniform_real_distribution<double> deg(-360, 360);
    for (int trial = 0; trial < 20; ++trial) {
        const glm::dmat3 R = rotationAboutAxis({g(rng), g(rng), g(rng)}, deg(rng));
        const Sh9Rgb turned = sh9Rotate(sh9Rotation(R), L);
        for (const Vec3& w : sphereDirections(200))
            expectRgbNear(sh9Eval(turned, w), sh9Eval(L, glm::transpose(R) * w), 1e-13);
    }
}

TEST(Sh9, RotationsInvertComposeAndKeepEachBandsNorm) {
    const Sh9Rgb L = randomSky(21);
    const Vec3 axis{0.2, -1, 0.7};
    const Sh9Rgb back = sh9RotateAboutAxis(sh9RotateAboutAxis(L, axis, 90), axis, -90);
    for (int k = 0; k < kSh9Count; ++k) expectRgbNear(back.c[k], L.c[k], 1e-14);

    const glm::dmat3 A = rotationAboutAxis({1, 0, 0}, 30), B = rotationAboutAxis({0, 1, 1}, -75);
    const Sh9Rgb twice = sh9Rotate(sh9Rotation(B), sh9Rotate(sh9Rotation(A), L));
    const Sh9Rgb once = sh9Rotate(sh9Rotation(B * A), L);
    for (int k = 0; k < kSh9Count; ++k) expectRgbNear(twice.c[k], once.c[k], 1e-14);

    const Sh9Rgb t = sh9RotateAboutAxis(L, {3, 1, -2}, 123);
    for (int ch = 0; ch < 3; ++ch) {
        const Sh9 a = L.channel(ch), b = t.channel(ch);
        EXPECT_EQ(a[0], b[0]);
        double n1a = 0, n1b = 0, n2a = 0, n2b = 0;
        for (int k = 1; k < 4; ++k) {
            n1a += a[k] * a[k];
            n1b += b[k] * b[k];
        }
        for (int k = 4; k < 9; ++k) {
            n2a += a[k] * a[k];
            n2b += b[k] * b[k];
        }
        EXPECT_NEAR(n1a, n1b, 1e-13);
        EXPECT_NEAR(n2a, n2b, 1e-13);
    }
}

TEST(Sh9, TurningASkyTurnsItsBrightSide) {
    // The format's sense: a sky brightest towards +x (L11 > 0), turned +90 degrees about
    // +z, is brightest towards +y (L1-1 > 0). A rotation by R^T instead of R fails here.
    Sh9Rgb L;
    L.c[0] = Rgb::gray(1);
    L.c[3] = Rgb::gray(0.5);
    const Sh9Rgb t = sh9RotateAboutAxis(L, {0, 0, 1}, 90);
    EXPECT_NEAR(t.c[1].r, 0.5, 1e-15);
    EXPECT_NEAR(t.c[3].r, 0.0, 1e-15);
    EXPECT_GT(sh9Eval(t, {0, 1, 0}).r, sh9Eval(t, {0, -1, 0}).r);
}

TEST(Sh9, IrradianceOfATurnedSkyIsTheIrradianceAtTheTurnedNormal) {
    // E'(n) = E(R^T n): what the viewer and the relit image will show when the sky turns.
    const Sh9Rgb L = graceCathedral();
    const glm::dmat3 R = rotationAboutAxis({0.5, 0.5, 1}, 200);
    const Sh9Rgb t = sh9Rotate(sh9Rotation(R), L);
    for (const Vec3& n : sphereDirections(100))
        expectRgbNear(sh9Irradiance(t, n), sh9Irradiance(L, glm::transpose(R) * n), 1e-14);
}

}  // namespace
}  // namespace radiosity
