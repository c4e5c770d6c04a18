#include "relight/pipeline/sky_fit.h"

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace relight {

using radiosity::kSh9Count;
using radiosity::Rgb;

namespace {

using Matrix = Eigen::MatrixXd;
using Vector = Eigen::VectorXd;

// Row p of channel ch's system: (rho_p / pi) (T_p, f_p).
Vector designRow(const SkyFitPixel& px, int ch, int unknowns) {
    Vector a(unknowns);
    const double scale = px.reflectance[ch] / std::numbers::pi;
    for (int k = 0; k < kSh9Count; ++k) a[k] = scale * px.transfer[static_cast<size_t>(k)];
    if (unknowns > kSh9Count) a[kSh9Count] = scale * px.sunFactor;
    return a;
}

void checkPixels(std::span<const SkyFitPixel> pixels, const SkyFitOptions& options) {
    if (pixels.empty()) throw std::invalid_argument("sky fit: no pixels");
    if (!(options.ridge >= 0) || !std::isfinite(options.ridge))
        throw std::invalid_argument("sky fit: the ridge must be finite and not negative");
    for (size_t p = 0; p < pixels.size(); ++p) {
        const SkyFitPixel& px = pixels[p];
        bool finite =
            px.radiance.isFinite() && px.reflectance.isFinite() && std::isfinite(px.sunFactor);
        for (const double t : px.transfer) finite = finite && std::isfinite(t);
        if (!finite)
            throw std::invalid_argument("sky fit: pixel " + std::to_string(p) +
                                        " has a value that is not finite");
    }
}

struct ChannelFit {
    Vector x;
    int rank = 0;
    bool regularised = false;
    int active = 0;  ///< constraints held at 0 (SkyFitOptions::nonNegative)
};

// The rows g_i of the constraints G x >= 0 on the unscaled unknowns: the sky's radiance in
// kNonNegativeDirections directions of a Fibonacci sphere (even spacing, no pole cluster),
// then the sun's irradiance when it is an unknown.
Matrix nonNegativeRows(int unknowns) {
    const int directions = kNonNegativeDirections;
    Matrix G = Matrix::Zero(directions + (unknowns > kSh9Count ? 1 : 0), unknowns);
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < directions; ++i) {
        const double z = 1.0 - 2.0 * (i + 0.5) / directions;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * i;
        const radiosity::Sh9 y = radiosity::sh9Basis({r * std::cos(phi), r * std::sin(phi), z});
        for (int k = 0; k < kSh9Count; ++k) G(i, k) = y[static_cast<size_t>(k)];
    }
    if (unknowns > kSh9Count) G(directions, kSh9Count) = 1.0;
    return G;
}

// min 1/2 y'Qy - r'y subject to G y >= 0, from y = Q^-1 r, Q positive definite. The dual in
// the multipliers lambda >= 0 is min 1/2 lambda' M lambda + lambda' G y0, M = G Q^-1 G', with
// y = y0 + Q^-1 G' lambda: projected Gauss-Seidel minimises it over one multiplier at a
// time exactly and clamps it at 0, which converges for M positive semi-definite (Cottle,
// Pang & Stone 1992, the linear complementarity problem, §5.2). A step d of multiplier i
// moves y by d Q^-1 g_i, whose Q-norm is |d| sqrt(M_ii): the sweeps end when the largest
// move is 1e-12 of y0's own Q-norm. Returns the number of constraints held at 0.
int holdNonNegative(const Matrix& Q, const Eigen::LDLT<Matrix>& ldlt, const Matrix& G, Vector& y) {
    if ((G * y).minCoeff() >= 0) return 0;       // the least squares already holds them
    const Matrix W = ldlt.solve(G.transpose());  // column i: Q^-1 g_i
    const Vector Mii = (G.array() * W.transpose().array()).rowwise().sum();
    const double size = std::sqrt(std::max(0.0, y.dot(Q * y)));
    const double tolerance = 1e-12 * std::max(size, 1e-300);
    Vector lambda = Vector::Zero(G.rows());
    constexpr int kMaxSweeps = 20000;
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
        double largest = 0;
        for (Eigen::Index i = 0; i < G.rows(); ++i) {
            if (!(Mii[i] > 0)) continue;  // a row Q^-1 cannot move: nothing to hold
            const double next = std::max(0.0, lambda[i] - G.row(i).dot(y) / Mii[i]);
            const double d = next - lambda[i];
            if (d == 0) continue;
            lambda[i] = next;
            y += d * W.col(i);
            largest = std::max(largest, std::abs(d) * std::sqrt(Mii[i]));
        }
        if (largest <= tolerance) break;
    }
    return static_cast<int>((lambda.array() > 0).count());
}

// Solves one channel's normal equations A^T A x = A^T b. The columns are scaled to unit
// norm first (D^-1 A^T A D^-1), so that the rank test and the ridge do not depend on the
// units of T and f; a column that is zero (no pixel constrains that unknown) keeps scale 1
// and shows as a zero eigenvalue. `nonNegative`: the rows G of SkyFitOptions::nonNegative
// (unscaled unknowns), or none.
ChannelFit solveChannel(std::span<const SkyFitPixel> pixels, int ch, int unknowns,
                        const SkyFitOptions& options, const Matrix& nonNegative) {
    Matrix N = Matrix::Zero(unknowns, unknowns);
    Vector rhs = Vector::Zero(unknowns);
    for (const SkyFitPixel& px : pixels) {
        const Vector a = designRow(px, ch, unknowns);
        N.selfadjointView<Eigen::Lower>().rankUpdate(a);
        rhs += a * px.radiance[ch];
    }
    N = N.selfadjointView<Eigen::Lower>();
    Vector scale = N.diagonal().cwiseSqrt();
    for (int j = 0; j < unknowns; ++j)
        if (!(scale[j] > 0)) scale[j] = 1;
    const Matrix S = scale.cwiseInverse().asDiagonal() * N * scale.cwiseInverse().asDiagonal();
    const Vector r = rhs.cwiseQuotient(scale);

    const Eigen::SelfAdjointEigenSolver<Matrix> eig(S, Eigen::EigenvaluesOnly);
    const double largest = eig.eigenvalues().maxCoeff();
    ChannelFit fit;
    for (int j = 0; j < unknowns; ++j)
        if (eig.eigenvalues()[j] > options.rankTolerance * largest) ++fit.rank;
    Matrix system = S;
    if (fit.rank < unknowns) {
        if (options.ridge == 0) return fit;  // the caller refuses
        // Tikhonov: the mean diagonal of S is 1 (unit columns), so ridge is relative.
        system += options.ridge * Matrix::Identity(unknowns, unknowns);
        fit.regularised = true;
    }
    const Eigen::LDLT<Matrix> ldlt(system);
    Vector y = ldlt.solve(r);
    if (nonNegative.rows() > 0)
        fit.active =
            holdNonNegative(system, ldlt, nonNegative * scale.cwiseInverse().asDiagonal(), y);
    fit.x = y.cwiseQuotient(scale);
    return fit;
}

std::string refusal(int rank, int unknowns, int ch) {
    static const char* kChannel[3] = {"red", "green", "blue"};
    return "sky fit: the pixels determine only " + std::to_string(rank) + " of the " +
           std::to_string(unknowns) + " unknowns (" + kChannel[ch] +
           " channel): their surfaces face too few ways, or see too little of the sky or "
           "sun; fit with a ridge (SkyFitOptions::ridge > 0) to regularise";
}

}  // namespace

SkyFitResult fitSky(std::span<const SkyFitPixel> pixels, const SkyFitOptions& options) {
    checkPixels(pixels, options);
    SkyFitResult result;
    result.unknowns = kSh9Count + (options.fitSun ? 1 : 0);
    result.rank = result.unknowns;
    // The constraints' rows, the same for every channel (none without nonNegative).
    const Matrix rows = options.nonNegative ? nonNegativeRows(result.unknowns) : Matrix();
    for (int ch = 0; ch < 3; ++ch) {
        const ChannelFit fit = solveChannel(pixels, ch, result.unknowns, options, rows);
        if (fit.rank < result.unknowns && !fit.regularised)
            throw SkyFitError(refusal(fit.rank, result.unknowns, ch));
        result.rank = std::min(result.rank, fit.rank);
        result.regularised = result.regularised || fit.regularised;
        result.activeConstraints += fit.active;
        for (int k = 0; k < kSh9Count; ++k) result.sky.c[static_cast<size_t>(k)][ch] = fit.x[k];
        if (options.fitSun) result.sunIrradiance[ch] = fit.x[kSh9Count];
    }
    // The residual of the fitted model, per channel.
    Rgb sum2;
    for (const SkyFitPixel& px : pixels) {
        const Rgb irradiance =
            radiosity::sh9Dot(px.transfer, result.sky) + result.sunIrradiance * px.sunFactor;
        const Rgb d = px.radiance - px.reflectance * irradiance * (1 / std::numbers::pi);
        sum2 += d * d;
    }
    const double n = static_cast<double>(pixels.size());
    result.rmsResidual = {std::sqrt(sum2.r / n), std::sqrt(sum2.g / n), std::sqrt(sum2.b / n)};
    return result;
}

}  // namespace relight
