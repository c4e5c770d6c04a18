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
};

// Solves one channel's normal equations A^T A x = A^T b. The columns are scaled to unit
// norm first (D^-1 A^T A D^-1), so that the rank test and the ridge do not depend on the
// units of T and f; a column that is zero (no pixel constrains that unknown) keeps scale 1
// and shows as a zero eigenvalue.
ChannelFit solveChannel(std::span<const SkyFitPixel> pixels, int ch, int unknowns,
                        const SkyFitOptions& options) {
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
    fit.x = system.ldlt().solve(r).cwiseQuotient(scale);
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
    for (int ch = 0; ch < 3; ++ch) {
        const ChannelFit fit = solveChannel(pixels, ch, result.unknowns, options);
        if (fit.rank < result.unknowns && !fit.regularised)
            throw SkyFitError(refusal(fit.rank, result.unknowns, ch));
        result.rank = std::min(result.rank, fit.rank);
        result.regularised = result.regularised || fit.regularised;
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
