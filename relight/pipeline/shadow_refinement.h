// Texture-based refinement for shadow boundaries (Loscos, Drettakis & Robert 2000, §4.2,
// Fig. 12).
//
// After the first radiosity solution, with the links from the lights at the leaves, every
// leaf is compared with its edge neighbours on the same polygon:
//   1. similar colour but different visibility of some light: subdivide (a shadow
//      boundary crosses the leaf, which the photo does not show yet at this size);
//   2. different colour but similar visibility: subdivide (the rays may have missed a
//      shadow the photo shows).
// A subdivided leaf whose children all see the lights as it does is merged back (case 2
// on a poster, not a shadow: Fig. 11(a)); otherwise its children are examined in turn.
// Refinement stops at the solver's minimum area and where leaves become too small to
// carry a colour (fewer than `minSamples` photo samples).
//
// Thresholds (documented units, scale-free, not fitted to a scene):
//   colourThreshold      two leaves have similar colours when the largest per-channel
//                        difference of their mean photo colours is below this fraction of
//                        the brighter one's largest channel (dimensionless). 0.2: a lamp
//                        that gives a fifth of a surface's light casts a visible shadow.
//   visibilityThreshold  two leaves see a light alike when their visibilities V = F V / F
//                        differ by less than this (V in [0, 1]). 0.25: twice the spread of
//                        V estimated with 16 rays at V = 0.5 (sqrt(0.25/16) = 0.125).
//   minShare             a light counts in the comparison when it gives at least this
//                        share of the pair's unoccluded direct light (dimensionless).
#pragma once

#include <functional>
#include <string>

#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/pipeline/leaf_texture.h"

namespace relight {

struct ShadowRefinementOptions {
    double colourThreshold = 0.2;
    double visibilityThreshold = 0.25;
    double minShare = 0.02;
    int minSamples = 32;    ///< photo samples a leaf needs to have a colour
    int maxSplits = 20000;  ///< a safety bound on the work
    /// The time at which its share of a time budget is spent (radiosity/stopwatch.h): no
    /// leaf is examined after it. The splits made so far are kept, each complete; the
    /// leaves not examined keep the solver's subdivision (fewer shadow boundaries refined).
    radiosity::Clock::time_point until = radiosity::Clock::time_point::max();
    std::function<void(const std::string&)> progress;
};

struct ShadowRefinementReport {
    int examined = 0;              ///< leaves compared with their neighbours
    int splitSameColour = 0;       ///< case 1 splits kept
    int splitDifferentColour = 0;  ///< case 2 splits kept
    int undone = 0;                ///< splits merged back (children saw the lights alike)
    int leavesBefore = 0, leavesAfter = 0;
    int waiting = 0;             ///< leaves left unexamined when `until` passed
    bool budgetReached = false;  ///< stopped at `until` with leaves still to examine
};

/// Refines `solver`'s leaves (solved, light links at the leaves) against the photo texture
/// `texture` (updated as leaves split), then re-gathers. Uses the lights' current
/// radiances to weigh them.
ShadowRefinementReport refineShadowBoundaries(radiosity::HierarchicalSolver& solver,
                                              LeafTexture& texture,
                                              const ShadowRefinementOptions& options = {});

}  // namespace relight
