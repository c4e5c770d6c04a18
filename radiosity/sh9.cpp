#include "radiosity/sh9.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace radiosity {

namespace {

constexpr double kPi = std::numbers::pi;
// The basis' constants (header): c0 = 1/(2 sqrt(pi)), c1 = sqrt(3/(4 pi)),
// c2 = sqrt(15/pi)/2, c20 = sqrt(5/pi)/4, c22 = sqrt(15/pi)/4.
const double kC0 = 0.5 / std::sqrt(kPi);
const double kC1 = std::sqrt(3.0 / (4.0 * kPi));
const double kC2 = 0.5 * std::sqrt(15.0 / kPi);
const double kC20 = 0.25 * std::sqrt(5.0 / kPi);
const double kC22 = 0.25 * std::sqrt(15.0 / kPi);

// Band 2 as quadratic forms: on the unit sphere Y_{4+m}(w) = w^T Q_m w with the symmetric,
// traceless Q_m below (3z^2 - 1 = 2z^2 - x^2 - y^2 there). A rotation turns the band-2
// part w^T Q w of a sky into w^T (R Q R^T) w, and the Q_m are orthogonal in the
// Frobenius product, so the new coefficients are <R Q R^T, Q_m> / <Q_m, Q_m>.
using Mat3 = std::array<std::array<double, 3>, 3>;  // [row][col]

Mat3 band2Form(int m) {
    Mat3 q{};
    switch (m) {
        case 0:
            q[0][1] = q[1][0] = 0.5 * kC2;
            break;  // xy
        case 1:
            q[1][2] = q[2][1] = 0.5 * kC2;
            break;  // yz
        case 2:     // 2z^2 - x^2 - y^2
            q[0][0] = q[1][1] = -kC20;
            q[2][2] = 2 * kC20;
            break;
        case 3:
            q[0][2] = q[2][0] = 0.5 * kC2;
            break;  // xz
        default:    // x^2 - y^2
            q[0][0] = kC22;
            q[1][1] = -kC22;
            break;
    }
    return q;
}

double frobenius(const Mat3& a, const Mat3& b) {
    double s = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += a[i][j] * b[i][j];
    return s;
}

// R Q R^T, with R given as glm's column-major R[col][row].
Mat3 conjugate(const glm::dmat3& R, const Mat3& q) {
    Mat3 out{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double s = 0;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) s += R[a][i] * q[a][b] * R[b][j];
            out[i][j] = s;
        }
    return out;
}

// Nodes and weights of n-point Gauss-Legendre quadrature on [-1, 1]: Newton's method on
// P_n from Chebyshev guesses, P_n and P_n' by the three-term recurrence.
void gaussLegendre(int n, std::vector<double>& z, std::vector<double>& w) {
    z.assign(static_cast<size_t>(n), 0.0);
    w.assign(static_cast<size_t>(n), 0.0);
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double dp = 1;
        for (int iter = 0; iter < 100; ++iter) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            // P_n' = n (x P_n - P_{n-1}) / (x^2 - 1); the nodes lie strictly inside (-1, 1).
            dp = n * (x * p1 - p0) / (x * x - 1);
            const double step = p1 / dp;
            x -= step;
            if (std::abs(step) < 1e-15) break;
        }
        z[static_cast<size_t>(i)] = x;
        w[static_cast<size_t>(i)] = 2 / ((1 - x * x) * dp * dp);
    }
}

}  // namespace

Sh9 Sh9Rgb::channel(int ch) const {
    Sh9 v{};
    for (int k = 0; k < kSh9Count; ++k) v[k] = c[k][ch];
    return v;
}

void Sh9Rgb::setChannel(int ch, const Sh9& v) {
    for (int k = 0; k < kSh9Count; ++k) c[k][ch] = v[k];
}

double sh9CosineLobe(int band) {
    // R&H 2001, Eq. 9: A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4.
    static constexpr double kA[3] = {kPi, 2 * kPi / 3, kPi / 4};
    if (band < 0 || band > 2) throw std::out_of_range("sh9CosineLobe: band must be 0, 1 or 2");
    return kA[band];
}

Sh9 sh9Basis(const Vec3& w) {
    const double x = w.x, y = w.y, z = w.z;
    return {kC0,
            kC1 * y,
            kC1 * z,
            kC1 * x,
            kC2 * x * y,
            kC2 * y * z,
            kC20 * (3 * z * z - 1),
            kC2 * x * z,
            kC22 * (x * x - y * y)};
}

double sh9Dot(const Sh9& a, const Sh9& b) {
    double s = 0;
    for (int k = 0; k < kSh9Count; ++k) s += a[k] * b[k];
    return s;
}

Rgb sh9Dot(const Sh9& t, const Sh9Rgb& L) {
    Rgb s;
    for (int k = 0; k < kSh9Count; ++k) s += L.c[k] * t[k];
    return s;
}

Rgb sh9Eval(const Sh9Rgb& L, const Vec3& w) {
    return sh9Dot(sh9Basis(w), L);
}

Sh9 sh9CosineTransfer(const Vec3& n) {
    Sh9 t = sh9Basis(n);
    for (int k = 0; k < kSh9Count; ++k) t[k] *= sh9CosineLobe(sh9Band(k));
    return t;
}

Rgb sh9Irradiance(const Sh9Rgb& L, const Vec3& n) {
    return sh9Dot(sh9CosineTransfer(n), L);
}

glm::dmat4 sh9IrradianceMatrix(const Sh9& L) {
    // R&H 2001, Eq. 12, with their constants from the basis: c1 = A_2 c22 (0.429043),
    // c2 = A_1 c1 (0.511664), c3 = 3 A_2 c20 (0.743125), c4 = A_0 c0 (0.886227),
    // c5 = A_2 c20 (0.247708).
    const double c1 = kPi / 4 * kC22, c2 = kPi / 3 * kC1, c3 = 3 * kPi / 4 * kC20;
    const double c4 = kPi * kC0, c5 = kPi / 4 * kC20;
    const double rows[4][4] = {{c1 * L[8], c1 * L[4], c1 * L[7], c2 * L[3]},
                               {c1 * L[4], -c1 * L[8], c1 * L[5], c2 * L[1]},
                               {c1 * L[7], c1 * L[5], c3 * L[6], c2 * L[2]},
                               {c2 * L[3], c2 * L[1], c2 * L[2], c4 * L[0] - c5 * L[6]}};
    glm::dmat4 M(0.0);
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) M[c][r] = rows[r][c];
    return M;
}

double sh9IrradianceQuadratic(const glm::dmat4& M, const Vec3& n) {
    const glm::dvec4 v(n, 1.0);
    return glm::dot(v, M * v);
}

Sh9 sh9Project(const std::function<double(const Vec3&)>& f, int zNodes) {
    Sh9Rgb rgb = sh9ProjectRgb([&f](const Vec3& w) { return Rgb::gray(f(w)); }, zNodes);
    return rgb.channel(0);
}

Sh9Rgb sh9ProjectRgb(const std::function<Rgb(const Vec3&)>& f, int zNodes) {
    if (zNodes < 1) throw std::invalid_argument("sh9Project: zNodes must be at least 1");
    std::vector<double> z, wz;
    gaussLegendre(zNodes, z, wz);
    const int phiSteps = 2 * zNodes;
    const double dPhi = 2 * kPi / phiSteps;
    Sh9Rgb out;
    for (int i = 0; i < zNodes; ++i) {
        const double zi = z[static_cast<size_t>(i)], s = std::sqrt(std::max(0.0, 1 - zi * zi));
        for (int j = 0; j < phiSteps; ++j) {
            const double phi = (j + 0.5) * dPhi;
            const Vec3 w{s * std::cos(phi), s * std::sin(phi), zi};
            // dw = dz dphi on the unit sphere.
            const Rgb v = f(w) * (wz[static_cast<size_t>(i)] * dPhi);
            const Sh9 y = sh9Basis(w);
            for (int k = 0; k < kSh9Count; ++k) out.c[k] += v * y[k];
        }
    }
    return out;
}

glm::dmat3 rotationAboutAxis(const Vec3& axis, double degrees) {
    const double len = glm::length(axis);
    if (!std::isfinite(len) || len < 1e-12)
        throw std::invalid_argument("rotation axis must be a finite, non-zero vector");
    if (!std::isfinite(degrees)) throw std::invalid_argument("rotation angle must be finite");
    const Vec3 a = axis / len;
    const double t = degrees * kPi / 180, c = std::cos(t), s = std::sin(t);
    // Rodrigues: R = c I + s [a]x + (1 - c) a a^T; glm stores R[col][row].
    const double K[3][3] = {{0, -a.z, a.y}, {a.z, 0, -a.x}, {-a.y, a.x, 0}};
    glm::dmat3 R(0.0);
    for (int r = 0; r < 3; ++r)
        for (int col = 0; col < 3; ++col)
            R[col][r] = (r == col ? c : 0.0) + s * K[r][col] + (1 - c) * a[r] * a[col];
    return R;
}

Sh9Rotation sh9Rotation(const glm::dmat3& R) {
    Sh9Rotation rot;
    // Band 1 is c1 (a . w) with a = (L11, L1-1, L10) along (x, y, z); L(R^T w) has
    // a' = R a. In the format's order (y, z, x) that is R with rows and columns permuted,
    // without signs: the format's basis has no Condon-Shortley phase. Libraries that have
    // it (google/spherical-harmonics) negate Y1-1, Y11, Y2-1 and Y21, so their coefficients
    // and band matrices differ from these by those four signs.
    static constexpr int kAxis[3] = {1, 2, 0};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) rot.band1[i][j] = R[kAxis[j]][kAxis[i]];
    // Band 2: column j is the turned form R Q_j R^T read back in the Q_i (see band2Form).
    std::array<Mat3, 5> q;
    for (int m = 0; m < 5; ++m) q[m] = band2Form(m);
    for (int j = 0; j < 5; ++j) {
        const Mat3 turned = conjugate(R, q[j]);
        for (int i = 0; i < 5; ++i)
            rot.band2[i][j] = frobenius(turned, q[i]) / frobenius(q[i], q[i]);
    }
    return rot;
}

Sh9 sh9Rotate(const Sh9Rotation& rot, const Sh9& L) {
    Sh9 out{};
    out[0] = L[0];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out[1 + i] += rot.band1[i][j] * L[1 + j];
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) out[4 + i] += rot.band2[i][j] * L[4 + j];
    return out;
}

Sh9Rgb sh9Rotate(const Sh9Rotation& rot, const Sh9Rgb& L) {
    Sh9Rgb out;
    out.c[0] = L.c[0];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) out.c[1 + i] += L.c[1 + j] * rot.band1[i][j];
    for (int i = 0; i < 5; ++i)
        for (int j = 0; j < 5; ++j) out.c[4 + i] += L.c[4 + j] * rot.band2[i][j];
    return out;
}

Sh9Rgb sh9RotateAboutAxis(const Sh9Rgb& L, const Vec3& axis, double degrees) {
    return sh9Rotate(sh9Rotation(rotationAboutAxis(axis, degrees)), L);
}

}  // namespace radiosity
