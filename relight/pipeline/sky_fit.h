// Sky fit: the nine RGB coefficients of an `environment` light (docs/scene-format.md,
// `"sh9": "estimate"`), and optionally the irradiance of a `sun`, from a photo's pixels
// (Wen, Liu & Huang 2003, §4, Eq. 16, with occlusion by Sloan, Kautz & Snyder 2002).
//
// A Lambertian pixel p of reflectance rho_p shows the radiance
//     I_p = (rho_p / pi) (sum_k T_pk L_k + f_p s)
// with T_p the sky's transfer vector at the surface it sees (radiosity/sky_transfer.h),
// L_k the sky's coefficients, s the sun's irradiance (on a surface facing it) and
// f_p = V_sun(p) max(0, n_p . d_sun) the share of it the surface receives. Wen et al. fit
// rho A_l L_lm for one constant albedo (their Eq. 16); with rho_p known per pixel and T_p
// in place of A_l Y_lm(n_p), the unknowns are the L_k (and s) themselves, linear, solved per
// channel by least squares: the normal equations, columns scaled to unit norm, by LDLT.
//
// Pixels that face only a few ways leave some coefficients undetermined (a wall facing +x
// sees E(+x) only: one number, not nine). The fit then refuses, naming how many
// unknowns the pixels determine, unless SkyFitOptions::ridge asks for a Tikhonov
// regularisation, which takes the smallest coefficients that fit.
#pragma once

#include <span>
#include <stdexcept>

#include "radiosity/rgb.h"
#include "radiosity/sh9.h"

namespace relight {

/// One observed pixel.
struct SkyFitPixel {
    radiosity::Rgb radiance;     ///< I_p, the photo's linear units
    radiosity::Rgb reflectance;  ///< rho_p per channel
    radiosity::Sh9 transfer{};   ///< T_p (radiosity/sky_transfer.h)
    double sunFactor = 0;        ///< f_p = V_sun max(0, n.d_sun); used with fitSun only
};

struct SkyFitOptions {
    /// Fit the sun's irradiance s as a tenth unknown.
    bool fitSun = false;
    /// Tikhonov weight, relative to the mean of the scaled normal matrix's diagonal (1):
    /// 0 refuses an undetermined system; e.g. 1e-6 takes, among the skies that fit, one with
    /// small coefficients along the undetermined directions.
    double ridge = 0;
    /// An eigenvalue of the scaled normal matrix below rankTolerance times the largest
    /// counts as zero: 1e-10 is a condition number of 1e5 of the scaled pixel matrix, where
    /// pixel noise of 1e-5 would already move the coefficients by their own size.
    double rankTolerance = 1e-10;
    /// Keep the sky's radiance L(w) = sum_k L_k Y_k(w) at or above 0 in every direction
    /// (tested at kNonNegativeDirections directions over the sphere) and the sun's
    /// irradiance at or above 0: light is not negative. Pixels that see the sky from a few
    /// ways only leave coefficients that the least squares sets from noise (a courtyard's
    /// fit gave a sky of radiance -0.53 where the true one is 0.02 at its lowest); the
    /// constraint bounds them by what the sky's mean allows. A convex quadratic programme,
    /// solved by its dual (projected Gauss-Seidel on the multipliers).
    bool nonNegative = false;
};

/// Directions (a Fibonacci sphere) at which SkyFitOptions::nonNegative holds the sky's
/// radiance at or above 0; between them a 9-term sky may dip by a little.
inline constexpr int kNonNegativeDirections = 512;

struct SkyFitResult {
    radiosity::Sh9Rgb sky;         ///< L_k, the photo's units
    radiosity::Rgb sunIrradiance;  ///< s (0 without fitSun)
    int unknowns = 0;              ///< 9, or 10 with fitSun
    int rank = 0;                  ///< of the system, the smallest over the channels
    bool regularised = false;      ///< rank < unknowns and the ridge was applied
    int activeConstraints = 0;     ///< nonNegative: directions held at 0, summed over channels
    radiosity::Rgb rmsResidual;    ///< sqrt(mean_p (I_p - model_p)^2) per channel
};

/// Thrown when the pixels do not determine the unknowns and no ridge is given.
struct SkyFitError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The least-squares sky (and sun) of the pixels. Throws std::invalid_argument for no
/// pixels, a value that is not finite, or a negative ridge; SkyFitError when the system
/// is rank-deficient and options.ridge is 0.
SkyFitResult fitSky(std::span<const SkyFitPixel> pixels, const SkyFitOptions& options = {});

}  // namespace relight
