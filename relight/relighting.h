// Relighting the photograph: the prepared state and the light edit.
//
// prepareRelighting() runs the pipeline once (Loscos et al. 2000, Fig. 5):
//   1. photo and camera: the first photo (sRGB decoded when the scene says so), checked
//      against the camera; the item buffer (polygon and point per sample, Embree);
//   2. the emittance of the lights whose radiance is "estimate" (relight/pipeline/emittance.h:
//      from the photo's pixels on the light's emitting face, else the power balance of
//      Eq. (1)-(2)); then a sun's irradiance and a sky's sh9 that are "estimate", fitted to
//      the photo's shading (relight/pipeline/sky_estimate.h); from then on the estimate stands for
//      the light's scene.json radiance: in the solution, in photoRadiance, and as the nominal
//      radiance of edits;
//   3. the radiosity solution of the photo's lights, and reflectance from the photo
//      (relight/pipeline/reflectance.h); texture-based refinement of shadow boundaries (§4.2,
//      relight/pipeline/shadow_refinement.h);
//   4. per-light responses of the solution (radiosity/light_response.h) and the
//      irradiance per light at every leaf vertex: the leaves' corners and those of their
//      display pieces (radiosity/leaf_mesh.h, displayPiecePixels;
//      relight/pipeline/vertex_lighting.h);
//   5. real-shadow removal (§4.3-4.4, relight/pipeline/shadow_removal.h): the display correction
//      factor D and the texture factor at the vertices, so that the unedited display is
//      the photo;
//   6. the display map (relight/display/ratio_display.h).
// renderEdit() then renders any setting of the real lights' radiances by superposition:
//   B(v) = rho sum_l L_l h_l(v),  pixel = T * B/D  (Eq. (3)),
// a weighted sum per vertex and one multiply-add per (pixel, vertex) pair.
// With shadowRefinement and shadowRemoval off this is the 1997 method (Drettakis et al.
// 1997, the paper's Fig. 9(c)): B/D at the vertices, D = B_orig, the radiosity of the
// photo's own lighting.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "radiosity/defaults.h"
#include "radiosity/direct_light.h"
#include "radiosity/leaf_mesh.h"
#include "radiosity/light_response.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/display/ratio_display.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/emittance.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/shadow_refinement.h"
#include "relight/pipeline/shadow_removal.h"
#include "relight/pipeline/sky_estimate.h"
#include "relight/pipeline/vertex_lighting.h"
#include "relight/prepared.h"

namespace relight {

struct RelightOptions {
    /// BF refinement threshold (radiosity/solver.h): finer than a solve's on its own, to
    /// follow the photo's shadows (radiosity/defaults.h).
    double epsilon = radiosity::kFineEpsilon;
    /// The solver's darkFloor (radiosity/solver.h): the threshold of a receiver darker than
    /// the mean is lowered with its radiosity, down to this fraction.
    double darkFloor = 0.1;
    /// The solver's perLightOracle (radiosity/solver.h): each light's own light refined to
    /// comparable relative accuracy, a light's weight raised at most by this factor; 0: off.
    double perLightOracle = 0;
    /// The solver's narrowClusterSources (radiosity/solver.h): a visible link from a cluster
    /// gathers from the part of it that faces the receiver. Off by default.
    bool narrowSources = false;
    /// The solver's refinement budget (radiosity/solver.h); 0: from the machine's memory.
    size_t maxLinks = 0, maxMemory = 0;
    /// Time budget of the preparation, seconds (0: none), counted from budgetStart
    /// (radiosity::TimeBudget) and split over its phases: the solver's refinement ends when
    /// kRefineShare of it has passed (SolverOptions::refineUntil), having refined the links
    /// of largest error first; the reflectance rounds when kRefineShare + kReflectanceShare
    /// has (estimatePolygonReflectance: fewer complete rounds), or after their own share
    /// kReflectanceShare when the phases before them overran theirs (the rounds set the
    /// photo's colours: cut to one on window_room under 5 s, the sky's light came in the
    /// first guess's colour, sun_off 0.08 -> 0.19). Each phase after them has
    /// a share too, ending at the cumulative sum of the shares up to its own, and a
    /// degraded but correct fallback once it is spent, announced on the terminal and
    /// flagged in PreparedImage::budgetReached (--report): the shadow-boundary refinement
    /// examines no more leaves (kShadowRefinementShare, counted from its own start when
    /// that is sooner: TimeBudget::phaseUntil; what the phases before it left goes to the
    /// phases after it, which have costs no fallback removes); the vertices' final gather keeps
    /// the PARTIAL links' V instead of casting rays (kVertexGatherShare); the per-pixel
    /// display's indirect gather casts fewer rays per vertex (kPixelGatherShare, at least
    /// 4 x 4; only with pixelGatherCut); real-shadow removal is skipped when the time left cannot
    /// hold it (kShadowRemovalShare: D is then the photo's lighting, the 1997 method).
    /// None by default: a caller that wants a bound asks for one, as the commands do
    /// (kCommandTimeBudget). Without one, what a preparation gives does not depend on the
    /// machine's speed or load: two preparations of a scene compared in one test, or in
    /// two processes, cannot differ because one of them took a fallback.
    double timeBudget = 0;
    /// `relight`'s and `relight-viewer`'s --time-budget default. It suits a 2-core laptop:
    /// the bundled scenes prepare in a few seconds, far inside it; a 10^5-10^6-triangle room
    /// ends its refinement within half a minute.
    static constexpr double kCommandTimeBudget = 60;
    /// Where timeBudget is counted from: a command sets its own start, so that loading the
    /// scene (parsing a large OBJ, the contact cut, the search for buried faces: 7 s of a
    /// 1.6 M-face model) is part of the budget, as it is part of what the user waits for.
    /// Unset (the clock's epoch): prepareRelighting()'s own start.
    radiosity::Clock::time_point budgetStart{};
    /// Bytes of memory the preparation may count on (0: radiosity::usableMemory(), the
    /// machine's or its container's): a scene whose expected need is larger is refused before
    /// the long work starts (relight/pipeline/memory_need.h). A caller that runs several
    /// preparations side by side gives each its share. Not part of the cache's key: it
    /// changes no result.
    size_t machineMemory = 0;
    /// `relight solve`'s default: the solve is the first look at a scene and the radiosity
    /// part of a preparation (its refinement and reflectance rounds, 65 % of the above).
    static constexpr double kSolveTimeBudget = 30;
    static constexpr double kRefineShare = 0.5;
    static constexpr double kReflectanceShare = 0.15;
    static constexpr double kShadowRefinementShare = 0.10;
    static constexpr double kVertexGatherShare = 0.08;
    static constexpr double kPixelGatherShare = 0.07;
    static constexpr double kShadowRemovalShare = 0.10;
    /// The cumulative share at which the shadow-boundary refinement, the vertices' gather,
    /// the per-pixel gather and real-shadow removal end (the last: the whole budget).
    static constexpr double kShadowRefinementEnds =
        kRefineShare + kReflectanceShare + kShadowRefinementShare;
    static constexpr double kVertexGatherEnds = kShadowRefinementEnds + kVertexGatherShare;
    static constexpr double kPixelGatherEnds = kVertexGatherEnds + kPixelGatherShare;
    static constexpr double kShadowRemovalEnds = kPixelGatherEnds + kShadowRemovalShare;
    static_assert(kShadowRemovalEnds > 1 - 1e-12 && kShadowRemovalEnds < 1 + 1e-12);
    int spp = 16;  ///< item-buffer samples per pixel, at most (sampleBudget)
    /// Samples over the whole image: fewer samples per pixel, and the estimates from the
    /// photo on a sub-grid of pixels, on large photos (SamplingPlan,
    /// relight/pipeline/item_buffer.h). 0: spp samples in every pixel, every pixel in the
    /// estimates.
    int64_t sampleBudget = kDefaultSampleBudget;
    int minRays = radiosity::kDefaultMinRays, maxRays = radiosity::kDefaultMaxRays;
    int reflectanceRounds = 12;
    /// Reflectance per leaf element from its texture after refinement
    /// (relight/pipeline/reflectance.h), for leaves with at least leafReflectanceSamples photo
    /// samples; off: per polygon.
    bool leafReflectance = true;
    int leafReflectanceSamples = 32;
    bool shadowRefinement =
        true;  ///< texture-based refinement (relight/pipeline/shadow_refinement.h)
    ShadowRefinementOptions refinement;
    bool shadowRemoval = true;  ///< real-shadow removal (relight/pipeline/shadow_removal.h)
    ShadowRemovalOptions removal;
    /// The display's resolution: a leaf is split (radiosity::LeafMesh) until each piece
    /// covers fewer than this many photo pixels (at most LeafMesh::kMaxSplits times), and
    /// the light is measured at every piece's corners. 0: leaf corners only.
    double displayPiecePixels = 4;
    /// Measure the direct light per pixel as well (pipeline/pixel_light.h), for the
    /// per-pixel display: shadow rays at every sample of every pixel.
    bool pixelLight = false;
    /// With pixelLight, the indirect light at each display vertex is gathered by this many
    /// rays at most (radiosity::rayGatherIndirect: each reads the radiosity of the leaf it
    /// hits), fewer where the mesh has so many vertices that vertices x rays would exceed
    /// indirectRayBudget (at least 16 each). 256 rays leave a noise of a few per cent per
    /// vertex, which the display's interpolation and the metric's 4 x 4 blocks average.
    int indirectRays = 256;
    int64_t indirectRayBudget = int64_t{1} << 24;
    /// Whether the per-pixel gather's share of the time budget (kPixelGatherShare) may cut
    /// its rays per vertex (down to 4 x 4). Off by default: on the staircase the cut from
    /// 7 x 7 to 4 x 4 took sconce_only from 0.435 to 0.511 (bench/RESULTS.md, 2026-11-27,
    /// sixth session); the other phases' fallbacks left its light edits as they were.
    bool pixelGatherCut = false;
    /// With pixelLight, merge the reflectance of all of the scene's photos per pixel for the
    /// light the first photo did not hold (pipeline/photo_merge.h; Loscos et al. 1999,
    /// Eq. (3)); off: the first photo alone (better on the bundled scenes but for a lamp
    /// photographed alone).
    bool mergePhotos = false;
    /// Weigh the refinement by the importance the photo's camera gives each surface
    /// (radiosity/solver.h, setCameraImportance; Smits, Arvo & Salesin 1992): what the
    /// photo sees and what lights it are refined first. Off by default while it is measured.
    bool importance = false;
    std::function<void(const std::string&)> progress;  ///< one line per step (may be empty)
};

/// The split rule of the display's leaf mesh: how many times a leaf is halved so that each
/// piece covers fewer than `piecePixels` photo pixels, counted from the leaf's texture
/// samples (samples x stride^2 / spp). Empty when piecePixels is 0.
radiosity::LeafMesh::SplitRule displaySplits(const LeafTexture& texture, const SamplingPlan& plan,
                                             double piecePixels);

/// The side k of the ray gather's k x k directions at each of `vertices` display vertices:
/// the largest with k^2 <= indirectRays and vertices k^2 <= indirectRayBudget, at least 4.
int indirectRaySide(const RelightOptions& o, size_t vertices);

/// The whole prepared state: what rendering needs (`prepared`, cacheable) and the solver
/// state behind it (for the gather path, edits that change geometry, and debug views).
struct Relighting {
    /// The scene as loaded, except that the lights whose radiance is "estimate" (still
    /// flagged in estimateRadiance) have their estimate in nominalRadiance and
    /// scene.lights: editRadiance(scene, edit) gives their edits. Its polygons are not here
    /// (scene.scene.polygons is empty) but in the solver, which owns them: a second copy
    /// was a quarter of a GB on a 1.6 M-face model. solver->scene().polygons holds them
    /// unchanged but for their reflectance, which the photo sets, followed by those of any
    /// object inserted (solver->scenePolygons() says how many are the scene's).
    SceneFile scene;
    EmittanceReport emittance;      ///< what was estimated and how (empty lights: nothing to do)
    SkyEstimateReport skyEstimate;  ///< the "estimate" sun and sky (any(): fitted)
    PreparedImage prepared;
    std::unique_ptr<radiosity::HierarchicalSolver> solver;
    ItemBuffer items;
    SamplingPlan sampling;  ///< the item buffer's spp and the estimates' pixel stride
    std::unique_ptr<radiosity::LeafMesh> mesh;
    std::unique_ptr<radiosity::LightResponses> responses;
    std::unique_ptr<LeafTexture> texture;  ///< the photo per leaf
    std::vector<int> surface;  ///< per polygon: its surface (pipeline/reflectance.h, surfaceOf)
    /// The reflectance rounds done, and whether their share of the time budget stopped them.
    int reflectanceRounds = 0;
    bool reflectanceBudgetReached = false;
    /// The later phases whose share of the time budget was spent (PreparedImage's bits 3-6).
    int phaseBudgetReached = 0;
    /// RelightOptions::timeBudget, from RelightOptions::budgetStart.
    radiosity::TimeBudget budget;
    ShadowRefinementReport refinement;
    VertexDirect direct;    ///< direct light per vertex and light, with and without blockers
    ShadowRemoval removal;  ///< empty when options.shadowRemoval is off
    /// The shadow rays of the per-point direct light (RelightOptions' minRays, maxRays), for
    /// the edits that measure it again (relight/dynamic/dynamic_relighting.h).
    radiosity::DirectLightOptions directOptions;
    /// The side of the ray gather's grid of directions at the display vertices
    /// (indirectRaySide(); 0: prepared without per-pixel light, the links' final gather).
    int gatherSide = 0;
    /// The leaf each of those rays met at each vertex (gatherSide^2 per vertex, -1: none), so
    /// that an inserted light's indirect change is gathered along them without casting them
    /// again (DynamicRelighting). Empty where they would take over kMaxRayHits entries.
    std::vector<int32_t> vertexRayHits;
};

/// At most this many recorded ray hits (4 bytes each: 64 MiB).
inline constexpr size_t kMaxRayHits = size_t{1} << 24;

/// Below this share of its emission meeting the front of a surface (radiosity::lightReach), a
/// light is reported: "almost none" rather than none, as a stray ray may graze an edge.
inline constexpr double kMinLightReach = 0.02;

/// One warning per light of the scene whose emitting side sees (almost) no part of the scene
/// (below the floor, facing away from the room, inside an object), naming scene.json, its key
/// and its name. `faces` and `vis`: the solver's scene and visibility (its lights in
/// scene.json's order). prepareRelighting() reports them through its progress.
std::vector<std::string> lightReachWarnings(const SceneFile& scene, const radiosity::Scene& faces,
                                            const radiosity::Visibility& vis);

/// The same for the virtual lights of an edit, once all of its parts are in the solver (a
/// virtual object may enclose a virtual light): `faces` and `vis` hold the scene's
/// `realLights` lights, then edit.addLights in order. Each warning names the edit file and
/// its key ("add_lights[0]").
std::vector<std::string> virtualLightReachWarnings(const EditFile& edit,
                                                   const radiosity::Scene& faces,
                                                   const radiosity::Visibility& vis,
                                                   size_t realLights);

/// The scene's first photo, linear (sRGB decoded when the scene says so), checked against
/// the camera's size; a non-finite pixel is an error naming it (it would spread through
/// every ratio that touches it). Throws InputError naming the file; also without photos.
Image loadFirstPhoto(const SceneFile& scene);
/// The same for photo `index` of scene.json's "photos".
Image loadPhoto(const SceneFile& scene, size_t index);

/// Runs the pipeline above on a loaded scene (loadScene); move the scene in where it is not
/// needed after (it holds the polygons, which go to the solver). Throws InputError for bad
/// input (photo missing, unreadable, of the wrong size, with NaN/Inf pixels; no photo at
/// all; a light whose radiance is "estimate" but that is off in the photo, or that cannot
/// be estimated: relight/pipeline/emittance.h). Estimates and warnings are reported through
/// options.progress.
std::unique_ptr<Relighting> prepareRelighting(SceneFile scene, const RelightOptions& options);

/// The real lights' radiances after `edit`: scene.json's radiance scaled or replaced for the
/// lights it names, the photo's state for the others (a light off in the photo that an edit
/// switches on gets its scene.json radiance, not the photo's zero).
/// `photoRadiance` is the PreparedImage's (maybe read from a cache): the nominal radiance of
/// an "estimate" light is its estimate, its radiance in the photo (it is on there), so the
/// scene may be the one loadScene() gave. Throws std::invalid_argument when photoRadiance
/// has the wrong size.
std::vector<radiosity::Rgb> editRadiance(const SceneFile& scene, const EditFile& edit,
                                         std::span<const radiosity::Rgb> photoRadiance);

/// Refuses an image relit for `edit` (`radiance`: the real lights', editRadiance()) that has
/// a value that is not finite, before anything is written: throws InputError naming the
/// edit's file and the key to blame, the radiance ("lights.A.scale", "lights.A.radiance",
/// "add_lights[0].radiance") of the brightest light the edit sets. A pixel is the photo
/// times the ratio of the edit's light to the photo's, so what overflows a float is a
/// radiance far beyond the photo's, and the brightest is the one. Throws std::runtime_error
/// when the edit sets no radiance (the fault is then not the edit's). `what` names the image
/// in the message.
void requireFiniteImage(const Image& image, const SceneFile& scene, const EditFile& edit,
                        std::span<const radiosity::Rgb> radiance,
                        const std::string& what = "the relit image");

}  // namespace relight
