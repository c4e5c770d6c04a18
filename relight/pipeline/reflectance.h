// Reflectance from the photo, per polygon, by inverse radiosity: the photo shows radiance
// L = rho H / pi on a Lambertian surface of irradiance H, so
//     rho_p = pi sum(L) / sum(H)      over the photo samples that see polygon p,
// with H from the radiosity solution of the lights of the photo. H itself depends on the
// reflectances (indirect light), so gather and estimate alternate (on the solver's links;
// they are refined for the final reflectances at the end). The plain fixed point
// rho <- pi L / H(rho) oscillates: where a surface gets a share s of its light indirectly,
// the error changes sign each round and shrinks only by s, and a ceiling lit only by
// bounced light (s ~ 1) never settles. Each round therefore moves half-way to the new
// estimate, rho <- (rho + pi L / H(rho)) / 2, which damps the error by (1 - s) / 2 per
// round for s in [0, 1]. Rounds stop when no reflectance moves by more than `tolerance`.
//
// This is the per-polygon version of Loscos et al. 1999, §4 (radiosity-based reflectance
// from a single image). Polygons the photo does not see keep the object's `reflectance`
// from scene.json, or else take the area-weighted mean of the estimated ones. Estimates
// are clamped to [0, kMaxReflectance]: a reflectance of 1 or more would make the radiosity
// system singular (B = E / (1 - rho)).
//
// Once the hierarchy is refined, each leaf element takes its own reflectance from its
// texture (Loscos et al. 2000, §4.2: "at the end of the refinement process, we set up all
// the necessary parameters: the reflectance, ..."): estimateLeafReflectance().
#pragma once

#include <algorithm>
#include <functional>
#include <span>
#include <string>

#include "radiosity/leaf_mesh.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/leaf_texture.h"
#include "relight/pipeline/lighting_buffer.h"

namespace relight {

/// Upper bound of every estimated reflectance: rho < 1 keeps B = E / (1 - rho) finite.
constexpr double kMaxReflectance = 0.98;
/// Each channel clamped to [0, kMaxReflectance].
inline radiosity::Rgb clampReflectance(radiosity::Rgb rho) {
    for (int c = 0; c < 3; ++c) rho[c] = std::clamp(rho[c], 0.0, kMaxReflectance);
    return rho;
}

/// Surfaces: polygons joined where they share a corner and their normals are within 25
/// degrees (radiosity::LeafMesh's rule), so that a wall a reconstruction cut into
/// triangles is one surface. Returns a surface id per polygon (union-find; a polygon's id is
/// one of its surface's polygons). Emitting faces are surfaces of their own.
std::vector<int> surfaceOf(const radiosity::Scene& scene);

/// Per object: the area-weighted mean of rho[p] over its polygons p with use(p), and the
/// area they cover (0, and a zero mean, for an object with none).
struct ObjectMeans {
    std::vector<radiosity::Rgb> rho;
    std::vector<double> area;
};
ObjectMeans objectMeans(const radiosity::Scene& scene, std::span<const radiosity::Rgb> rho,
                        const std::function<bool(int)>& use);

struct ReflectanceReport {
    int rounds = 0;
    int polygonsSeen = 0;       ///< polygons with enough photo samples, or their surface
    int polygonsDefaulted = 0;  ///< reflecting polygons the photo does not see
    double lastChange = 0;      ///< largest reflectance change in the last round
    /// The rounds stopped early because their time budget (`seconds` or `until`) was spent:
    /// the solution is that of the rounds done, each of them complete.
    bool budgetReached = false;
    /// The set-up could not end by ReflectanceOptions::until: nothing was estimated,
    /// every polygon keeps its reflectance and the solver its solution (rounds 0).
    bool skipped = false;
    /// surfaceOf(the solver's scene), which the estimate pooled over: later steps that pool
    /// over surfaces take it from here rather than joining the polygons again.
    std::vector<int> surface;
};

struct ReflectanceOptions {
    int rounds = 12;          ///< estimate/solve rounds at most
    int minSamples = 16;      ///< photo samples a polygon needs to be estimated on its own
    double tolerance = 1e-3;  ///< rounds stop when no reflectance moves by more
    /// A time budget for the rounds, from the call (0: none): a round is never cut in the
    /// middle (it sets every polygon's reflectance, then solves); a round starts only when
    /// one as long as the last fits in what is left (at least one always runs after the
    /// set-up), and the report says when one did not.
    double seconds = 0;
    /// A deadline for the whole estimate (the largest time point: none). The set-up (the
    /// photo's samples summed per polygon, their gather points' final gathers, whose cost is
    /// set by the links above the points) is given up when it has not ended by then: the
    /// report says `skipped`. Unlike `seconds`, no round is owed: a round begins only when
    /// one as long as the last fits before it, and its irradiance sums are given up when it
    /// passes (that round then changes nothing, and may be the first). `relight solve` sets
    /// it, whose whole run has a bound.
    radiosity::Clock::time_point until = radiosity::Clock::time_point::max();
    /// Told each round's largest change and time (progress on the terminal); may be empty.
    std::function<void(const std::string&)> progress;
};

/// `options.rounds` estimate/solve rounds from a solved `solver`. H per sample is the direct
/// light of `lighting` (relight/pipeline/lighting_buffer.h) plus indirect light gathered from
/// the solver at up to 256 of each polygon's gather points per round. Only pixels whose
/// samples all see one reflecting polygon, with no emitting face within one pixel and finite
/// values, are used, on the lighting buffer's sub-grid of pixels (its stride). A polygon
/// needs `minSamples` photo samples to be estimated; one with fewer takes the estimate pooled
/// over its surface (the polygons joined by shared corners within 25 degrees: a wall that
/// a reconstruction cut into small triangles) when that has enough.
ReflectanceReport estimatePolygonReflectance(radiosity::HierarchicalSolver& solver,
                                             const SceneFile& sceneFile, const ItemBuffer& items,
                                             const LightingBuffer& lighting, const Image& photo,
                                             const ReflectanceOptions& options = {});

/// A leaf's reflectance from its texture, rho = pi c / H (Lambertian: the photo shows
/// L = rho H / pi), with c the mean photo colour of the leaf's samples and H the mean of the
/// irradiance at its corners (`H` per vertex of `mesh`, radiosity units; the display
/// interpolates between the same corners). Not clamped. False, and `rho` untouched, where the
/// leaf has fewer than `minSamples` samples or no light in some channel (guard: H = 0 tells
/// nothing of its colour).
bool leafReflectanceFromTexture(const radiosity::Hierarchy& h, const radiosity::LeafMesh& mesh,
                                const LeafTexture& texture, std::span<const radiosity::Rgb> H,
                                int leaf, int minSamples, radiosity::Rgb* rho);

/// Sets the reflectance of every leaf of a reflecting polygon that leafReflectanceFromTexture
/// can estimate, clamped to [0, kMaxReflectance]; the others keep their polygon's. Pulls the
/// clusters' averages; the caller runs the radiosity step. Returns the leaves set.
int estimateLeafReflectance(radiosity::HierarchicalSolver& solver, const radiosity::LeafMesh& mesh,
                            const LeafTexture& texture, std::span<const radiosity::Rgb> H,
                            int minSamples);

}  // namespace relight
