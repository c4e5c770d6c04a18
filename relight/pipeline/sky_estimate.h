// The strengths of a sun and a sky whose scene.json strength is "estimate"
// (docs/scene-format.md: a sun's "irradiance", an environment's "sh9"), fitted to the first
// photo before the radiosity solution that needs them (Wen, Liu & Huang 2003, §4).
//
// Each component k of such a light (the sun; each of the sky's 9 coefficients) is one light
// of the scene (radiosity/emitter.h), so its light at a photo pixel p is linear in its
// strength s_k:
//     I_p = (rho_p / pi) (sum_k s_k pi G_pk + H0_p)
// with G_pk the component's direct light at unit strength per pixel (the LightingBuffer's,
// shadows from its own rays: the sun's disc, the sky's hemisphere; the sky's pi G_p is the
// transfer vector of Sloan, Kautz & Snyder 2002) and H0_p the rest of the irradiance: the
// direct light of the lights of known strength and the indirect light of the radiosity
// solution. The fit (relight/pipeline/sky_fit.h) is the least squares of I_p on those
// columns, per channel, over the photo's clean pixels (usablePixels).
//
// The indirect light depends on the strengths, so fit and solve alternate: round 0 without
// indirect light (the first guess), then `rounds` times: set the strengths, solve (the
// first time) or re-gather, gather the indirect light at each pixel, fit again. In an
// open scene the indirect share is small and two rounds settle it.
//
// rho_p: the photo alone fixes only rho L, not each: a sky twice as bright on surfaces half
// as light shows the same photo (Wen et al. fit rho A_l L_lm with one albedo for the same
// reason). The fit therefore alternates with the reflectance: the first fit takes the
// solver's (scene.json's object reflectance, else "average_reflectance", else 0.5); then,
// `alternations` times, each object's reflectance is the engine's estimate
// rho = pi sum(I) / sum(H) over its pixels (relight/pipeline/reflectance.h) under the fitted
// lights, and the lights are fitted again. One reflectance per object, as Wen's one albedo:
// an object whose faces face several ways (a box, the walls) then tells the sky's directions
// apart, which a reflectance per polygon would absorb. The scale (the gauge of rho L) is
// set by keeping the pixels' mean reflectance luminance at the model's: the user's guess
// of the scene's reflectance sets the light's scale, as in Eq. (2') of emittance.h. An edit
// that scales or turns the sky is rendered by ratios and does not depend on it; an edit that
// sets absolute strengths does.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/rgb.h"
#include "radiosity/sh9.h"
#include "radiosity/solver.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

struct SkyEstimateOptions {
    /// Fit-and-gather rounds after the direct-only first fit.
    int rounds = 2;
    /// Reflectance-and-fit alternations per round (below); 0: the model's reflectance.
    int alternations = 20;
    /// The fit's rank test and Tikhonov weight (SkyFitOptions). A scene seen from above
    /// (a courtyard: the ground and walls) never shows the sky below the horizon, and the
    /// directions of the 10 unknowns that only it would fix are nearly null, not exactly:
    /// with SkyFitOptions' defaults (1e-10, a condition number of 1e5) data/courtyard's fit
    /// took them at full rank and gave coefficients of +-5 for a true 0.3 (bench/RESULTS.md,
    /// 2026-11-26 third session). An eigenvalue below 1e-4 of the largest (a condition number
    /// of 100 of the unit-scaled pixel matrix) counts as undetermined, and the ridge of 1e-3
    /// (relative to the unit diagonal) then takes small coefficients along those directions
    /// while moving the well determined ones by about 1e-3 of themselves.
    double rankTolerance = 1e-4;
    double ridge = 1e-3;
    /// SkyFitOptions::nonNegative: the fitted sky's radiance at or above 0 in every
    /// direction, the sun's irradiance too. The ridge alone left the courtyard's
    /// undetermined coefficients at 0.2-0.6 where the true ones are below 0.06, a sky of
    /// radiance -0.53 in places (bench/RESULTS.md, 2026-11-28, fourteenth session).
    bool nonNegative = true;
    /// The pixel stride of the photo's sub-grid (SamplingPlan::stride).
    int stride = 1;
    radiosity::DirectLightOptions direct;
    std::function<void(const std::string&)> progress;  ///< may be empty
};

struct SkyEstimateReport {
    std::string skyName, sunName;  ///< empty: that light is not estimated
    radiosity::Sh9Rgb sky;         ///< fitted coefficients (photo units)
    radiosity::Rgb sun;            ///< fitted irradiance (photo units)
    int pixels = 0;                ///< photo pixels fitted
    int rounds = 0;                ///< fits done (1 + rounds of indirect light)
    int rank = 0, unknowns = 0;    ///< of the last fit (SkyFitResult)
    bool regularised = false;
    int activeConstraints = 0;   ///< SkyFitResult::activeConstraints of the last fit
    radiosity::Rgb rmsResidual;  ///< of the last fit, photo radiance units
    std::vector<std::string> warnings;

    bool any() const { return !skyName.empty() || !sunName.empty(); }
    /// Lines for the log: the fitted strengths, pixels, rank, residual.
    std::vector<std::string> summary() const;
};

/// Whether `sf` has a sun or sky whose strength is "estimate".
bool hasSkyEstimate(const SceneFile& sf);

/// Fits the "estimate" suns and skies of `sf` to `photo` (the first photo, linear) through
/// `solver` (constructed on sf.scene, not necessarily solved) and `items`, its item buffer.
/// Writes the strengths into sf.nominalRadiance and sf.scene.lights and leaves the solver
/// with them (solved when rounds > 0). Throws InputError naming scene.json's key for more
/// than one estimated sun or sky, or when the photo's pixels do not constrain them (no clean
/// pixel lit by them).
SkyEstimateReport estimateSkyFromPhoto(SceneFile& sf, radiosity::HierarchicalSolver& solver,
                                       const ItemBuffer& items, const Image& photo,
                                       const SkyEstimateOptions& options = {});

}  // namespace relight
