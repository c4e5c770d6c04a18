// PreparedImage: everything that rendering a light edit needs, and nothing else.
//
// It is the output of the preparation pipeline (relight/relighting.h) as flat arrays, so
// that it can be cached on disk (relight prepare) and an edit renders without the solver:
//   per vertex v    B(v) = sum_l L_l h_l(v)                       (superposition)
//                   r(v) = k(v) * B(v) / D(v)                     (Eq. (3), guarded)
//   per pixel       out  = T_orig * sum_v w_v r(v)  (+ emitting faces)
// where k(v) = T_final / T_orig is the texture correction of real-shadow removal at the
// vertex (Loscos et al. 2000, §4.4: the paper modulates the texture by factors computed at
// the leaf vertices), 1 where no shadow is removed. Keeping T_orig and k apart instead of
// storing T_final makes the unedited display give back the photo exactly (k B/D = 1 at
// every vertex), whatever the interpolation.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/display/ratio_display.h"
#include "relight/io/image.h"
#include "relight/pipeline/vertex_lighting.h"

namespace relight {

struct PrepareTimes {
    double itemBuffer = 0, solve = 0, reflectance = 0, refinement = 0, responses = 0,
           vertexLighting = 0, shadowRemoval = 0, displayMap = 0;  ///< seconds
};

/// "item buffer 0.019, solve 0.013, ...": the time of each step, in seconds.
std::string stepTimes(const PrepareTimes& t);

struct PreparedImage {
    Image photo;                                ///< T_orig: the first photo, linear
    DisplayMap display;                         ///< per pixel: vertices and weights, emitting faces
    VertexLighting lighting;                    ///< per vertex and light: h_l(v), per unit radiance
    std::vector<radiosity::Rgb> D;              ///< per vertex: display correction factor
    std::vector<radiosity::Rgb> textureFactor;  ///< per vertex: k = T_final / T_orig
    std::vector<radiosity::Rgb> photoRadiance;  ///< per light: its radiance in the photo
    // Counts for reports.
    int leaves = 0, links = 0;
    /// The refinement budget (HierarchicalSolver's stats): whether it was reached, the
    /// solver's nodes and links in bytes, and the budget in force.
    int budgetReached = 0;
    uint64_t solverBytes = 0, maxLinks = 0, maxMemory = 0;
    PrepareTimes times;

    size_t vertexCount() const { return D.size(); }
};

/// Per-vertex irradiance B for the lights' radiances (one per light; photo units).
std::vector<radiosity::Rgb> vertexIrradiance(const PreparedImage& p,
                                             std::span<const radiosity::Rgb> radiance);

/// The display ratio k H/D per vertex for vertex irradiance H (displayRatio() times the
/// texture correction k of real-shadow removal).
std::vector<radiosity::Rgb> vertexRatio(const PreparedImage& p, std::span<const radiosity::Rgb> H);

/// The relit photo for the lights' radiances (superposition path).
Image renderEdit(const PreparedImage& p, std::span<const radiosity::Rgb> radiance);
/// The same into `out`, reused from edit to edit (renderRatio).
void renderEdit(const PreparedImage& p, std::span<const radiosity::Rgb> radiance, Image& out);

}  // namespace relight
