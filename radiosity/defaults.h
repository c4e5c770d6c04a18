// The defaults that more than one layer offers, each in one place: the options structs
// (TransferOptions, DirectLightOptions, SolverOptions, relight's RelightOptions) and the
// commands' flags (`relight solve`, `prepare`, `render`, the viewer) take them from here.
#pragma once

namespace radiosity {

/// Visibility rays: a first round of kDefaultMinRays for a link (or for a point and a light
/// polygon); when they disagree (penumbra), up to kDefaultMaxRays in all.
inline constexpr int kDefaultMinRays = 4;
inline constexpr int kDefaultMaxRays = 16;

/// BF refinement threshold (solver.h) of a solve on its own: SolverOptions and `relight
/// solve`.
inline constexpr double kDefaultEpsilon = 1e-3;
/// The finer threshold of a solve that a photo is relit from (relight's RelightOptions,
/// `relight prepare` and `render`, the viewer): the display interpolates B and D across
/// the leaves, so the leaves must be small enough to follow the shadow boundaries the
/// photo shows, where a solve on its own only needs the energy right. Changing either
/// value changes figures that bench/RESULTS.md records.
inline constexpr double kFineEpsilon = 1e-4;

}  // namespace radiosity
