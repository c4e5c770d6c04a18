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
//
// The confidence display (DisplayMode::confidence; `relight render --display confidence`)
// splits the edit's
// irradiance in two: B_kept, the light of the lamps that were on in the photo (at their new
// radiance), and B_new, the light the photo did not hold (lamps that were off, virtual
// lamps, and the change virtual objects make). With the photo's confidence K(v) (Loscos et
// al. 1999, §4.1-4.3; relight/pipeline/confidence.h) and the model's reflectance rho(v):
//   r(v) = k (B_kept + K B_new) / D            multiplies the photo, as above
//   a(v) = (1 - K) rho B_new / pi              is added (radiance)
//   pixel = T_orig * sum_v w_v r(v) + sum_v w_v a(v)
// Where K = 1 this is the ratio display; where the photo's lamps did not light a point
// (K = 0), the light an edit brings there is the model's, rho B / pi, rather than the photo
// times a ratio whose denominator the model knows least there. An edit of the photo's own
// lamps (B_new = 0) is the ratio display whatever K: the unedited display stays the photo.
// The ratio display stays the default: the confidence display is better on the bundled
// scenes' virtual lights (Cornell virtual_light_only 0.139 -> 0.084) but worse on a room cut
// into 22 k jittered triangles (0.013 -> 0.027), whose textures it flattens where K is low
// (bench/RESULTS.md, 2026-11-25).
//
// The per-pixel display (DisplayMode::pixel; relight/pipeline/pixel_light.h) divides the
// photo by the light each pixel received, the direct light measured per pixel:
//   pixel = T sum_l L_l h_l(p) / sum_l L_l(photo) h_l(p)
// Better than the ratio display on every edit of every bundled scene (room back_off 0.0167
// -> 0.0125; with virtual parts through relight/dynamic/dynamic_relighting.h), it needs a
// preparation with RelightOptions::pixelLight; `relight render` uses it by default.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/display/ratio_display.h"
#include "relight/io/image.h"
#include "relight/pipeline/pixel_light_table.h"
#include "relight/pipeline/vertex_lighting.h"

namespace relight {

struct PrepareTimes {
    double itemBuffer = 0, solve = 0, reflectance = 0, refinement = 0, responses = 0,
           vertexLighting = 0, shadowRemoval = 0, displayMap = 0;  ///< seconds
};

/// "item buffer 0.019, solve 0.013, ...": the time of each step, in seconds.
std::string stepTimes(const PrepareTimes& t);

/// One line per later phase whose share of a --time-budget of `seconds` was spent, with its
/// fallback, from PreparedImage::budgetReached's bits 3-6 (none: empty).
std::vector<std::string> phaseBudgetLines(int budgetReached, double seconds);

struct PreparedImage {
    Image photo;                                ///< T_orig: the first photo, linear
    DisplayMap display;                         ///< per pixel: vertices and weights, emitting faces
    VertexLighting lighting;                    ///< per vertex and light: h_l(v), per unit radiance
    std::vector<radiosity::Rgb> D;              ///< per vertex: display correction factor
    std::vector<radiosity::Rgb> textureFactor;  ///< per vertex: k = T_final / T_orig
    std::vector<radiosity::Rgb> photoRadiance;  ///< per light: its radiance in the photo
    std::vector<float> confidence;              ///< per vertex: K in [0, 1] (confidence.h)
    /// Per-pixel direct light (pipeline/pixel_light.h), only when prepared with
    /// RelightOptions::pixelLight: pi Gbar per pixel and light, and the indirect part of
    /// each vertex's response per light (a gather by rays, RelightOptions::indirectRays).
    /// Empty otherwise.
    std::vector<float> pixelDirect;
    std::vector<radiosity::Rgb> vertexIndirect;
    /// The reflectance merged from all of the scene's photos, 3 floats per pixel
    /// (pipeline/photo_merge.h), when it has more than one and RelightOptions::mergePhotos;
    /// empty otherwise (the per-pixel display then reads the first photo alone).
    std::vector<float> pixelReflectance;
    std::vector<radiosity::Rgb> modelReflectance;  ///< per vertex: the polygon's rho
    /// With per-pixel light (empty otherwise), for Wen et al.'s display
    /// (DisplayMode::wen, relight/display/wen_display.h): each pixel's normal, 3 floats, the
    /// unit mean of the polygon normals of its samples that see a reflecting surface (0
    /// where none does); and per light, the sky coefficient k (0-8) it scales when it is a
    /// component of an environment light, -1 for any other light.
    std::vector<float> pixelNormal;
    std::vector<int> skyCoefficient;
    /// Derived, not cached (derivePhotoPixels): the photo per pixel as the per-pixel
    /// display's pooled reflectance reads it; empty without per-pixel light.
    PhotoPixels photoPixels;
    /// Derived with it: the per-pixel light edit's table (pipeline/pixel_light_table.h).
    PixelLightTable pixelTable;
    // Counts for reports.
    int leaves = 0, links = 0;
    /// The refinement budget (HierarchicalSolver's stats): whether it was reached, the
    /// solver's nodes and links in bytes, and the budget in force.
    /// bit 0: the refinement's budget was reached; bit 1: it was the time budget; bit 2:
    /// the reflectance rounds stopped at their share of the time budget; the bits below
    /// (kPhaseBudget...): a later phase's share was spent, and it took its fallback.
    int budgetReached = 0;
    /// The shadow-boundary refinement stopped with leaves still to examine.
    static constexpr int kShadowRefinementBudget = 8;
    /// The vertices' final gather kept the PARTIAL links' V for the vertices after its share.
    static constexpr int kGatherBudget = 16;
    /// The per-pixel display's indirect rays per vertex were cut to fit their share.
    static constexpr int kPixelGatherBudget = 32;
    /// Real-shadow removal was skipped (D = B of the photo, the 1997 method): its share
    /// could not hold it.
    static constexpr int kShadowRemovalBudget = 64;
    /// The leaves' reflectance from their texture was skipped (the polygons' estimate
    /// kept): the vertices' final gather had used up its share.
    static constexpr int kLeafReflectanceBudget = 128;
    /// The preparation ended past the budget (more than kOverrunTolerance of it): every
    /// phase with a fallback had taken it, and the work that none removes (the hierarchy,
    /// the lamps' links to every face, the per-light responses) grows with the mesh.
    static constexpr int kBudgetOverrun = 256;
    static constexpr double kOverrunTolerance = 1.05;
    uint64_t solverBytes = 0, maxLinks = 0, maxMemory = 0;
    PrepareTimes times;

    size_t vertexCount() const { return D.size(); }
};

/// Fills p.photoPixels and p.pixelTable from its per-pixel light
/// (relight/pipeline/pixel_light.h, photoPixels; pixel_light_table.h); clears them without
/// per-pixel light.
void derivePhotoPixels(PreparedImage& p);

/// Per-vertex irradiance B for the lights' radiances (one per light; photo units).
std::vector<radiosity::Rgb> vertexIrradiance(const PreparedImage& p,
                                             std::span<const radiosity::Rgb> radiance);

/// How the relit photo is made from the vertex values (above).
enum class DisplayMode {
    ratio,       ///< Loscos et al. 2000: T k B / D everywhere
    confidence,  ///< the ratio where the photo is trusted, the model where it is not
    pixel,       ///< per-pixel direct light (pipeline/pixel_light.h): relight render's default
    /// The ratio map of ../shared/seeds/000 (Eq. 3): L_r = L_o I_r / I_o per pixel with I the
    /// lights' direct irradiance alone (the per-pixel display's h_l(p) = pi Gbar_l(p), no
    /// indirect part, no pooled reflectance): the paper's variant, kept to compare with.
    ratioMap,
    /// Wen, Liu & Huang 2003 (../shared/seeds/002, Eqs. (13), (15)): the per-pixel display with the
    /// environment light's part the unoccluded irradiance E(n) of its 9 coefficients at the
    /// pixel's normal (Ramamoorthi & Hanrahan 2001, Eq. 7), for the photo's sky and the
    /// edit's, in place of the occluded transfer and its bounces; every other light as in
    /// DisplayMode::pixel. Kept to compare with (relight/display/wen_display.h).
    wen,
};
/// "ratio", "confidence", "pixel", "ratio-map", "wen"; and back (std::invalid_argument naming the
/// modes).
const char* displayModeName(DisplayMode mode);
/// Whether the display draws per pixel (pixel, ratio-map, wen): it needs a preparation with
/// per-pixel light (RelightOptions::pixelLight) and has no values per vertex.
bool drawsPerPixel(DisplayMode mode);
DisplayMode parseDisplayMode(const std::string& name);

/// The edit's irradiance per vertex in the two parts the confidence display weighs apart:
/// the photo's lamps at their new radiance (kept) and the rest (fresh: lamps off in the
/// photo; the caller adds what virtual parts change).
struct SplitIrradiance {
    std::vector<radiosity::Rgb> kept, fresh;
};
SplitIrradiance splitIrradiance(const PreparedImage& p, std::span<const radiosity::Rgb> radiance);

/// What the display multiplies the photo by, and adds to it, per vertex.
struct VertexDisplay {
    std::vector<radiosity::Rgb> ratio;
    std::vector<radiosity::Rgb> added;  ///< empty for the ratio display
};
/// The display values for irradiance kept + fresh (above). Without confidence data (a map
/// built by hand) the confidence display is the ratio display.
VertexDisplay vertexDisplay(const PreparedImage& p, const SplitIrradiance& H, DisplayMode mode);

/// The display ratio k H/D per vertex for vertex irradiance H (displayRatio() times the
/// texture correction k of real-shadow removal).
std::vector<radiosity::Rgb> vertexRatio(const PreparedImage& p, std::span<const radiosity::Rgb> H);

/// The relit photo for the lights' radiances (superposition path). DisplayMode::pixel needs
/// a preparation with per-pixel light (std::invalid_argument otherwise).
Image renderEdit(const PreparedImage& p, std::span<const radiosity::Rgb> radiance,
                 DisplayMode mode = DisplayMode::ratio);
/// The same into `out`, reused from edit to edit (renderRatio).
void renderEdit(const PreparedImage& p, std::span<const radiosity::Rgb> radiance, Image& out,
                DisplayMode mode = DisplayMode::ratio);
/// DisplayMode::ratioMap (000 Eq. 3): the ratio display, then the per-pixel display with
/// the direct irradiance alone where the per-pixel display draws.
void renderRatioMap(const PreparedImage& p, std::span<const radiosity::Rgb> radiance, Image& out);
/// DisplayMode::pixel by the general path (renderRatio, then renderPixelLight in double),
/// which renderEdit() takes only where the fast table (p.pixelTable) cannot serve: the
/// reference the fast path is tested and timed against.
void renderPixelEditReference(const PreparedImage& p, std::span<const radiosity::Rgb> radiance,
                              Image& out);

}  // namespace relight
