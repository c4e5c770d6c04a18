#include "relight/relighting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "radiosity/final_gather.h"
#include "radiosity/light_reach.h"
#include "radiosity/parallel.h"
#include "radiosity/stopwatch.h"
#include "relight/io/json_reader.h"
#include "relight/pipeline/confidence.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/memory_need.h"
#include "relight/pipeline/photo_merge.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/pipeline/reflectance.h"

namespace relight {

using radiosity::Rgb;

namespace {

using radiosity::Clock;
constexpr auto& since = radiosity::secondsSince;  // seconds since t0 (radiosity/stopwatch.h)

}  // namespace

Image loadFirstPhoto(const SceneFile& sf) {
    return loadPhoto(sf, 0);
}

Image loadPhoto(const SceneFile& sf, size_t index) {
    if (sf.photos.empty())
        throw InputError((sf.dir / "scene.json").string() +
                         ": key \"photos\": the scene has no photo to relight");
    if (index >= sf.photos.size())
        throw std::invalid_argument("loadPhoto: photo " + std::to_string(index) + " of " +
                                    std::to_string(sf.photos.size()));
    const PhotoSpec& ph = sf.photos[index];
    Image photo = readImage(ph.file, ph.encoding == PhotoSpec::Encoding::srgb);
    if (photo.width != sf.camera.width || photo.height != sf.camera.height)
        throw InputError(ph.file.string() + ": photo is " + std::to_string(photo.width) + "x" +
                         std::to_string(photo.height) + " but the camera is " +
                         std::to_string(sf.camera.width) + "x" + std::to_string(sf.camera.height));
    for (int y = 0; y < photo.height; ++y)
        for (int x = 0; x < photo.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (!std::isfinite(photo.at(x, y)[c]))
                    throw InputError(ph.file.string() + ": pixel (" + std::to_string(x) + ", " +
                                     std::to_string(y) + ") is not a finite number");
    return photo;
}

namespace {

/// The warning for light `l` of `faces` when too little of its emission meets a surface;
/// `where` names the file and key it comes from. Empty when it lights the scene.
std::string reachWarning(const radiosity::Scene& faces, const radiosity::Visibility& vis, size_t l,
                         const std::string& where) {
    const radiosity::LightReach reach = radiosity::lightReach(faces, vis, static_cast<int>(l));
    if (reach.fraction >= kMinLightReach) return {};
    char share[160];
    std::snprintf(share, sizeof share, "%d of %d rays from its face meet the front of a surface",
                  reach.hits, reach.rays);
    return where + ": light \"" + faces.lights[l].name + "\": its emitting side sees " +
           (reach.hits == 0 ? "no" : "almost no") + " part of the scene (" + share +
           "; is it below the floor, facing away or inside an object?): its power is lost to "
           "the room";
}

}  // namespace

std::vector<std::string> lightReachWarnings(const SceneFile& sf, const radiosity::Scene& faces,
                                            const radiosity::Visibility& vis) {
    std::vector<std::string> out;
    const std::string file = (sf.dir / "scene.json").string();
    size_t entry = 0;  // its index in scene.json's "lights" (a sky is 9 lights here)
    for (size_t l = 0; l < faces.lights.size(); ++l) {
        if (l > 0 && faces.lights[l].component == 0) ++entry;
        // A light that is not faces (sun, sky, point lamp) has no face to cast from.
        if (faces.lights[l].emitter) continue;
        std::string w =
            reachWarning(faces, vis, l, file + ": key \"lights[" + std::to_string(entry) + "]\"");
        if (!w.empty()) out.push_back(std::move(w));
    }
    return out;
}

std::vector<std::string> virtualLightReachWarnings(const EditFile& edit,
                                                   const radiosity::Scene& faces,
                                                   const radiosity::Visibility& vis,
                                                   size_t realLights) {
    std::vector<std::string> out;
    for (size_t i = 0; i < edit.addLights.size() && realLights + i < faces.lights.size(); ++i) {
        if (edit.addLights[i].emitter) continue;  // no face to cast from
        std::string w =
            reachWarning(faces, vis, realLights + i,
                         edit.file.string() + ": key \"add_lights[" + std::to_string(i) + "]\"");
        if (!w.empty()) out.push_back(std::move(w));
    }
    return out;
}

int indirectRaySide(const RelightOptions& o, size_t vertices) {
    int64_t rays = std::max(o.indirectRays, 16);
    if (vertices > 0) rays = std::min(rays, o.indirectRayBudget / static_cast<int64_t>(vertices));
    int side = 4;
    while (static_cast<int64_t>(side + 1) * (side + 1) <= rays) ++side;
    return side;
}

radiosity::LeafMesh::SplitRule displaySplits(const LeafTexture& texture, const SamplingPlan& plan,
                                             double piecePixels) {
    if (!(piecePixels > 0)) return {};
    const double pixelsPerSample =
        static_cast<double>(plan.stride) * plan.stride / std::max(plan.spp, 1);
    return [&texture, pixelsPerSample, piecePixels](int leaf) {
        double pixels = texture.samples(leaf) * pixelsPerSample;
        int s = 0;
        for (; pixels >= piecePixels && s < radiosity::LeafMesh::kMaxSplits; ++s) pixels /= 4;
        return s;
    };
}

namespace {

void say(const RelightOptions& o, const std::string& message) {
    if (o.progress) o.progress(message);
}

/// "75 %": a cumulative share of --time-budget, for the terminal.
std::string percentOfBudget(double share) {
    return std::to_string(static_cast<int>(std::lround(100 * share))) + " %";
}

radiosity::DirectLightOptions directLightOptions(const RelightOptions& o) {
    radiosity::DirectLightOptions dlo;
    dlo.minRays = o.minRays;
    dlo.maxRays = o.maxRays;
    return dlo;
}

/// The solver's scene: sf.scene with its polygons moved, not copied (a quarter of a GB on a
/// 1.6 M-face model), leaving sf.scene.polygons empty (Relighting::scene says why).
radiosity::Scene takeSolverScene(SceneFile& sf) {
    radiosity::Scene s;
    s.polygons = std::move(sf.scene.polygons);
    sf.scene.polygons = {};  // moved from: empty, said rather than assumed
    s.objects = sf.scene.objects;
    s.lights = sf.scene.lights;
    return s;
}

/// Step 1: the first photo, the solver's scene, and the item buffer the camera casts on it.
void readPhotoAndCastItems(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    P.photo = loadFirstPhoto(r.scene);
    radiosity::SolverOptions so;
    so.epsilon = o.epsilon;
    so.darkFloor = o.darkFloor;
    so.perLightOracle = o.perLightOracle;
    so.narrowClusterSources = o.narrowSources;
    so.maxLinks = o.maxLinks;
    so.maxMemory = o.maxMemory;
    so.refineUntil = r.budget.until(RelightOptions::kRefineShare);
    so.transfer.minRays = o.minRays;
    so.transfer.maxRays = o.maxRays;
    so.progress = o.progress;
    auto t0 = Clock::now();
    r.solver = std::make_unique<radiosity::HierarchicalSolver>(takeSolverScene(r.scene), so);
    for (const std::string& w :
         lightReachWarnings(r.scene, r.solver->scene(), r.solver->visibility()))
        say(o, "warning: " + w);
    say(o, "item buffer");
    r.sampling = planSampling(r.scene.camera.width, r.scene.camera.height, o.spp, o.sampleBudget);
    r.items =
        castItemBuffer(r.scene.camera, r.solver->scene(), r.solver->visibility(), r.sampling.spp);
    std::vector<double> seen = seenPolygons(r.items, r.solver->scene());
    if (o.importance) r.solver->setCameraImportance(seen);
    r.solver->setCameraSeen(std::move(seen));
    P.times.itemBuffer = since(t0);
}

/// Step 2: the lights whose radiance is "estimate", estimated before the solve, which needs
/// their emittance; from here on they are lights of known radiance (nominal = estimate).
/// Then the lights' radiances in the photo.
void estimateLightsFromPhoto(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    if (std::find(r.scene.estimateRadiance.begin(), r.scene.estimateRadiance.end(), true) !=
        r.scene.estimateRadiance.end()) {
        say(o, "emittance of the \"estimate\" lights");
        r.emittance = estimateEmittance(r.scene, r.solver->scene(), r.items, P.photo);
        for (const std::string& w : r.emittance.warnings) say(o, "  warning: " + w);
        for (const std::string& line : r.emittance.summary()) say(o, "  " + line);
        std::vector<Rgb> radiance(r.scene.scene.lights.size());
        for (size_t l = 0; l < radiance.size(); ++l) {
            if (r.scene.estimateRadiance[l] && !r.scene.scene.lights[l].emitter) {
                // On in the photo (checkEstimableLights), so the photo's state is the estimate.
                r.scene.nominalRadiance[l] = r.emittance.lights[l].radiance;
                r.scene.scene.lights[l].radiance = r.emittance.lights[l].radiance;
            }
            radiance[l] = r.scene.scene.lights[l].radiance;
        }
        r.solver->setLightRadiances(radiance);  // not solved yet: sets the emittance only
    }
    if (hasSkyEstimate(r.scene)) {
        // After the quads (their light is then known): the sun and sky "estimate", fitted to
        // the photo's shading (relight/pipeline/sky_estimate.h).
        say(o, "sun and sky \"estimate\": least squares on the photo (Wen et al. 2003, §4)");
        SkyEstimateOptions so;
        so.stride = r.sampling.stride;
        so.direct = directLightOptions(o);
        so.progress = o.progress;
        r.skyEstimate = estimateSkyFromPhoto(r.scene, *r.solver, r.items, P.photo, so);
        for (const std::string& w : r.skyEstimate.warnings) say(o, "  warning: " + w);
        for (const std::string& line : r.skyEstimate.summary()) say(o, "  " + line);
    }
    P.photoRadiance.resize(r.scene.scene.lights.size());
    for (size_t l = 0; l < P.photoRadiance.size(); ++l)
        P.photoRadiance[l] = r.scene.scene.lights[l].radiance;  // the photo's state
}

/// Step 3, first part: the radiosity solution of the photo's lights, then the reflectance of
/// each polygon from the photo.
void solveAndEstimateReflectance(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    auto t0 = Clock::now();
    say(o, "radiosity solution of the photo's lights");
    r.solver->solve();
    P.times.solve = since(t0);
    if (const auto st = r.solver->stats(); st.timeBudgetReached) {
        char msg[200];
        std::snprintf(
            msg, sizeof msg,
            "warning: the refinement's time budget (until %g s, half of --time-budget) was "
            "reached at %d links: the solution is coarser where the oracle's error "
            "was smallest",
            o.timeBudget * RelightOptions::kRefineShare, st.links);
        say(o, msg);
    } else if (st.budgetReached)
        say(o, "warning: the refinement budget was reached (" + std::to_string(st.links) +
                   " links, " + std::to_string(st.memoryBytes >> 20) +
                   " MiB): the solution is coarser where the oracle's error was smallest");

    t0 = Clock::now();
    say(o, "reflectance from the photo");
    const LightingBuffer lighting =
        computeLightingBuffer(r.items, *r.solver, directLightOptions(o), r.sampling.stride);
    ReflectanceOptions ro;
    ro.rounds = o.reflectanceRounds;
    // Until their end of the budget, and at least their own share of it when the phases
    // before overran theirs (a contended machine): the rounds set the photo's colours, and
    // cut to one they leave the indirect light coloured by the first guess.
    ro.seconds = r.budget.secondsUntilAtLeast(
        RelightOptions::kRefineShare + RelightOptions::kReflectanceShare,
        RelightOptions::kReflectanceShare);
    ro.progress = [&o](const std::string& m) { say(o, m); };
    const ReflectanceReport rep =
        estimatePolygonReflectance(*r.solver, r.scene, r.items, lighting, P.photo, ro);
    r.surface = rep.surface;
    r.reflectanceRounds = rep.rounds;
    r.reflectanceBudgetReached = rep.budgetReached;
    say(o, "  " + std::to_string(rep.rounds) + " reflectance round(s)" +
               (rep.budgetReached ? ": their share of --time-budget was spent, stopped after a "
                                    "complete round"
                                  : ""));
    // Per-pixel direct light, when asked, from these same rays where they cover every pixel.
    if (o.pixelLight && lighting.stride == 1)
        P.pixelDirect = pixelDirect(r.items, r.solver->scene(), lighting);
    P.times.reflectance = since(t0);
}

/// Step 3, second part: the photo per leaf, and the texture-based refinement of shadow
/// boundaries (§4.2) when it is on.
void refineAlongPhotoShadows(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    auto t0 = Clock::now();
    r.texture = std::make_unique<LeafTexture>(
        r.solver->hierarchy(), r.solver->scene(), r.items, P.photo,
        usablePixels(r.items, r.solver->scene(), P.photo, r.sampling.stride));
    if (o.shadowRefinement) {
        say(o, "texture-based refinement of shadow boundaries");
        ShadowRefinementOptions ro = o.refinement;
        ro.progress = o.progress;
        // Its own share at most, even when the reflectance left time: the phases after it
        // (the responses, the vertices' gather without rays, the per-pixel display) cost
        // what they cost, and on a real stair hall they overran the budget by the 7 s this
        // phase had taken beyond its share.
        ro.until =
            std::min(ro.until, r.budget.phaseUntil(t0, RelightOptions::kShadowRefinementShare,
                                                   RelightOptions::kShadowRefinementEnds));
        r.refinement = refineShadowBoundaries(*r.solver, *r.texture, ro);
        say(o, "  " + std::to_string(r.refinement.splitSameColour) + " + " +
                   std::to_string(r.refinement.splitDifferentColour) + " splits kept, " +
                   std::to_string(r.refinement.undone) + " undone; " +
                   std::to_string(r.refinement.leavesAfter) + " leaves");
        if (r.refinement.budgetReached) {
            r.phaseBudgetReached |= PreparedImage::kShadowRefinementBudget;
            say(o, "  warning: its share of --time-budget (" +
                       percentOfBudget(RelightOptions::kShadowRefinementShare) + ", until " +
                       percentOfBudget(RelightOptions::kShadowRefinementEnds) +
                       " at the latest) was spent: " + std::to_string(r.refinement.waiting) +
                       " leaves were not examined (fewer shadow boundaries refined)");
        }
    }
    P.times.refinement = since(t0);
}

/// Step 4: the per-light responses, the display's leaf mesh and the lighting per light at
/// its vertices; then, when it is on, each leaf's reflectance from its texture against the
/// irradiance at its corners, a radiosity step, and the lighting again (its indirect part
/// changed; the direct part, and its rays, are kept).
void lightLeafVertices(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    auto t0 = Clock::now();
    say(o, "per-light responses");
    r.responses = std::make_unique<radiosity::LightResponses>(*r.solver);
    P.times.responses = since(t0);

    t0 = Clock::now();
    r.mesh = std::make_unique<radiosity::LeafMesh>(
        r.solver->hierarchy(), displaySplits(*r.texture, r.sampling, o.displayPiecePixels));
    say(o, "lighting at " + std::to_string(r.mesh->vertices().size()) + " leaf vertices");
    P.lighting =
        measureVertexLighting(*r.solver, *r.mesh, *r.responses, directLightOptions(o), r.direct,
                              o.progress, r.budget.until(RelightOptions::kVertexGatherEnds));
    say(o, "  final gather: " + std::to_string(r.direct.gather.sharedLinks) +
               " far links gathered at " + std::to_string(r.direct.gather.samples()) +
               " element corners, " + std::to_string(r.direct.gather.nearLinks) +
               " near links per vertex (" + std::to_string(r.direct.gather.leafSharedLinks) +
               " of them at the corners of leaves of many vertices); " +
               std::to_string(r.direct.gather.terms()) + " terms kept");
    if (r.direct.gather.withoutRays > 0) {
        r.phaseBudgetReached |= PreparedImage::kGatherBudget;
        say(o, "  warning: its share of --time-budget (until " +
                   percentOfBudget(RelightOptions::kVertexGatherEnds) +
                   ") was spent: " + std::to_string(r.direct.gather.withoutRays) +
                   " corners and vertices gathered without visibility rays (their partly "
                   "occluded links' mean visibility)");
    }
    P.times.vertexLighting = since(t0);

    if (!o.leafReflectance) return;
    // A refinement of the polygons' estimate that costs a radiosity step, the responses
    // and the vertices' gather again (4 s on the stair hall): past the vertex gather's
    // share, the phases after it would overrun theirs. The polygons' reflectances stand.
    if (r.budget.seconds > 0 && Clock::now() >= r.budget.until(RelightOptions::kVertexGatherEnds)) {
        r.phaseBudgetReached |= PreparedImage::kLeafReflectanceBudget;
        say(o,
            "  warning: the leaves' reflectance from their texture skipped: the share of "
            "--time-budget until " +
                percentOfBudget(RelightOptions::kVertexGatherEnds) +
                " was spent (each polygon keeps its estimate from the photo)");
        return;
    }
    t0 = Clock::now();
    const std::vector<Rgb> H = vertexIrradiance(P, P.photoRadiance);
    const int set =
        estimateLeafReflectance(*r.solver, *r.mesh, *r.texture, H, o.leafReflectanceSamples);
    say(o, "reflectance of " + std::to_string(set) + " leaf elements from their texture");
    r.solver->gatherPushPull();
    r.responses = std::make_unique<radiosity::LightResponses>(*r.solver, std::move(r.responses));
    P.lighting = regatherVertexLighting(*r.solver, *r.mesh, *r.responses, r.direct);
    P.times.reflectance += since(t0);
    char msg[96];
    std::snprintf(msg, sizeof msg, "  radiosity, responses and vertex lighting again: %.1f s",
                  since(t0));
    say(o, msg);
}

/// The indirect part of vertices [from, to)'s responses per light by r.gatherSide^2 rays
/// each (radiosity::rayGatherResponses), into P.vertexIndirect and r.vertexRayHits; at
/// from == 0 both are laid out afresh for r.gatherSide.
void gatherVertexIndirect(Relighting& r, size_t L, size_t from, size_t to) {
    PreparedImage& P = r.prepared;
    const auto& mesh = *r.mesh;
    const auto& solver = *r.solver;
    const size_t nv = mesh.vertices().size();
    const size_t rays = static_cast<size_t>(r.gatherSide) * static_cast<size_t>(r.gatherSide);
    if (from == 0) {
        P.vertexIndirect.assign(nv * L, Rgb{});
        r.vertexRayHits.clear();
        if (nv * rays <= kMaxRayHits) r.vertexRayHits.assign(nv * rays, -1);
    }
    radiosity::parallelForChunks(to - from, 64, [&](size_t first, size_t last) {
        for (size_t v = from + first; v != from + last; ++v) {
            const int p = mesh.vertices()[v].polygon;
            if (solver.scene().polygons[static_cast<size_t>(p)].light >= 0) continue;
            int32_t* hits = r.vertexRayHits.empty() ? nullptr : r.vertexRayHits.data() + v * rays;
            radiosity::rayGatherResponses(
                solver, *r.responses, p, mesh.insidePoint(static_cast<int>(v)),
                P.vertexIndirect.data() + v * L, r.gatherSide, v, nullptr, hits);
        }
    });
}

/// The rays' side for all `nv` vertices to fit in `left` seconds when `pilot` of them took
/// `seconds` at `side`: the time is linear in the rays (each a ray cast and a leaf's
/// responses read); never below 4 (16 rays, indirectRaySide's floor) nor above `side`.
int fewerRaysSide(int side, double seconds, size_t pilot, size_t nv, double left) {
    if (!(seconds > 0) || pilot == 0) return side;
    const double projected = seconds * static_cast<double>(nv - pilot) / static_cast<double>(pilot);
    if (projected <= left) return side;
    const double perRay = seconds / (static_cast<double>(pilot) * side * side);
    const double rays = left / (perRay * static_cast<double>(nv));
    return std::clamp(static_cast<int>(std::floor(std::sqrt(std::max(rays, 0.0)))), 4, side);
}

/// Step 4b, when asked: the direct light per pixel (unless step 3 had it already, with the
/// photo sampled in full), and the indirect part of the vertices' responses before
/// real-shadow removal scales their light links.
void lightPixels(Relighting& r, const RelightOptions& o) {
    if (!o.pixelLight) return;
    PreparedImage& P = r.prepared;
    const auto t0 = Clock::now();
    if (P.pixelDirect.empty()) {
        say(o, "direct light per pixel");
        P.pixelDirect = measurePixelDirect(r.items, *r.solver, directLightOptions(o));
    }
    P.pixelNormal = pixelNormals(r.items, r.solver->scene());
    P.skyCoefficient = skyCoefficients(r.solver->scene());
    // The indirect part of each vertex's response per light, gathered by rays that read
    // the leaves' radiosity where they land (radiosity::rayGatherResponses), not through
    // the links' sources: the per-pixel display divides the photo by it, and where the
    // photo is lit by bounced light only, the links' coarse sources read 10-18 % too
    // much light (bench/RESULTS.md, 2026-11-26).
    const size_t nv = r.mesh->vertices().size();
    const size_t L = r.responses->lights() > 0 ? static_cast<size_t>(r.responses->lights()) : 0;
    r.gatherSide = indirectRaySide(o, nv);
    // A pilot over the first vertices, timed, when a time budget holds: if the rest would
    // overrun the share, every vertex is gathered again with fewer rays (the pilot's are
    // thrown away: the rays' layout per vertex is one side for all).
    const size_t pilot = r.budget.seconds > 0 && o.pixelGatherCut
                             ? std::min(nv, std::max<size_t>(1024, nv / 50))
                             : nv;
    const auto tPilot = Clock::now();
    gatherVertexIndirect(r, L, 0, pilot);
    const double left = r.budget.secondsUntil(RelightOptions::kPixelGatherEnds);
    const int side =
        pilot < nv ? fewerRaysSide(r.gatherSide, since(tPilot), pilot, nv, left) : r.gatherSide;
    if (side < r.gatherSide) {
        r.phaseBudgetReached |= PreparedImage::kPixelGatherBudget;
        say(o, "  warning: the indirect rays per vertex at " + std::to_string(r.gatherSide) +
                   " x " + std::to_string(r.gatherSide) +
                   " would overrun their share of "
                   "--time-budget (until " +
                   percentOfBudget(RelightOptions::kPixelGatherEnds) +
                   "): " + std::to_string(side) + " x " + std::to_string(side) + " instead");
        r.gatherSide = side;
        gatherVertexIndirect(r, L, 0, nv);
    } else {
        gatherVertexIndirect(r, L, pilot, nv);
    }
    P.times.vertexLighting += since(t0);
    char msg[128];
    std::snprintf(msg, sizeof msg,
                  "  per-pixel display: direct light and %d x %d indirect rays per vertex, %.1f s",
                  r.gatherSide, r.gatherSide, since(t0));
    say(o, msg);
}

/// Whether real-shadow removal fits in the time its share leaves: it solves the light's
/// responses three times (relight/pipeline/shadow_removal.h: after k_inter, C_link and
/// C_umbra), each as long as step 4's (PrepareTimes::responses), and gathers them from the
/// kept terms (no ray). Always without a time budget; never once the budget is spent.
bool removalFits(const Relighting& r) {
    if (!(r.budget.seconds > 0)) return true;
    const auto end = r.budget.until(RelightOptions::kShadowRemovalEnds);
    return Clock::now() < end && r.budget.secondsUntil(RelightOptions::kShadowRemovalEnds) >
                                     3 * r.prepared.times.responses;
}

/// Step 5: real-shadow removal (§4.3-4.4) gives D and the texture factor; without it, the
/// 1997 method: D is the photo's own lighting, so the unedited display is the photo (B/D = 1).
void removeShadowsForDisplay(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    auto t0 = Clock::now();
    if (o.shadowRemoval && !removalFits(r)) {
        r.phaseBudgetReached |= PreparedImage::kShadowRemovalBudget;
        say(o, "warning: real-shadow removal skipped: its share of --time-budget (until " +
                   percentOfBudget(RelightOptions::kShadowRemovalEnds) +
                   ") cannot hold its three radiosity steps; D is the photo's lighting (the "
                   "1997 method)");
    }
    if (o.shadowRemoval && !(r.phaseBudgetReached & PreparedImage::kShadowRemovalBudget)) {
        say(o, "real-shadow removal");
        ShadowRemovalOptions ro = o.removal;
        ro.progress = o.progress;
        r.removal =
            removeRealShadows(*r.solver, r.responses,
                              {*r.mesh, *r.texture, P.photoRadiance, P.lighting, r.direct}, ro);
        say(o, "  " + std::to_string(r.removal.occluded) + " occluded leaves, " +
                   std::to_string(r.removal.frontier) + " on the frontier, " +
                   std::to_string(r.removal.referenced) + " with a reference; " +
                   std::to_string(r.removal.partialVertices) + " vertices with C_link, " +
                   std::to_string(r.removal.umbraVertices) + " with C_umbra");
        P.lighting = r.removal.lighting;
        P.D = r.removal.D;
        P.textureFactor = r.removal.kFinal;
    } else {
        P.D = vertexIrradiance(P, P.photoRadiance);
        P.textureFactor.assign(P.D.size(), Rgb::gray(1.0));
    }
    P.times.shadowRemoval = since(t0);
    // The vertices' gather terms served the lightings above; edits gather afresh.
    r.direct.gather = {};
    // What the confidence display needs (relight/prepared.h, relight/pipeline/confidence.h).
    P.confidence = vertexConfidence(r.direct, P.photoRadiance);
    P.modelReflectance =
        vertexModelReflectance(*r.mesh, r.solver->scene(), r.surface, P.confidence);
}

/// Step 6b, with the per-pixel light and more than one photo: the reflectance of all of
/// them merged per pixel (Loscos et al. 1999, Eq. (3); pipeline/photo_merge.h).
void mergeAllPhotos(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    if (!o.pixelLight || !o.mergePhotos || r.scene.photos.size() < 2 || P.pixelDirect.empty())
        return;
    const auto t0 = Clock::now();
    say(o, "reflectance merged from " + std::to_string(r.scene.photos.size()) + " photos");
    std::vector<Image> images;
    images.reserve(r.scene.photos.size());
    images.push_back(P.photo);
    for (size_t i = 1; i < r.scene.photos.size(); ++i) images.push_back(loadPhoto(r.scene, i));
    std::vector<MergePhoto> photos(images.size());
    const auto& lights = r.scene.scene.lights;
    for (size_t i = 0; i < images.size(); ++i) {
        photos[i].image = &images[i];
        photos[i].radiance.assign(lights.size(), Rgb{});
        for (size_t l = 0; l < lights.size(); ++l) {
            const auto& on = r.scene.photos[i].lightsOn;
            if (std::find(on.begin(), on.end(), lights[l].name) == on.end()) continue;
            // An "estimate" lamp (on in the first photo) at its estimate.
            photos[i].radiance[l] =
                r.scene.estimateRadiance[l] ? P.photoRadiance[l] : r.scene.nominalRadiance[l];
        }
    }
    photos[0].radiance = P.photoRadiance;  // the display's own photo radiances
    const PhotoMerge m =
        mergePhotos(P.display, photos, P.pixelDirect, P.vertexIndirect, ratioFloor(P.D));
    P.pixelReflectance = m.reflectance;
    char line[160];
    std::snprintf(line, sizeof line, "  %d pixels, the first photo's share of the confidence %.2f",
                  m.pixels, m.firstPhotoShare);
    say(o, line);
    P.times.displayMap += since(t0);
}

/// Step 6: the display map, and the solver's figures for the report.
void mapDisplay(Relighting& r, const RelightOptions& o) {
    PreparedImage& P = r.prepared;
    auto t0 = Clock::now();
    P.display = buildDisplayMap(r.items, *r.mesh, r.solver->scene());
    if (const int n = trustPhotoAtEmitters(P.display, P.photo, P.photoRadiance); n > 0)
        say(o, "warning: " + std::to_string(n) +
                   " pixels on a lamp's emitting face do not show the lamp in the photo (is the "
                   "lamp where scene.json says?); they are kept as in the photo");
    // Each vertex weighed by what it shows in the photo, rho B_photo (luminance), so that a
    // pixel across a lit and a dark surface divides sums (ratio_display.h).
    const std::vector<Rgb> Bphoto = vertexIrradiance(P, P.photoRadiance);
    const bool rho = P.modelReflectance.size() == Bphoto.size();
    std::vector<double> shown(Bphoto.size());
    for (size_t v = 0; v < shown.size(); ++v) {
        const Rgb s = rho ? P.modelReflectance[v] * Bphoto[v] : Bphoto[v];
        shown[v] = s.luminance();
    }
    weighByPhotoRadiance(P.display, shown);
    P.times.displayMap = since(t0);
    const auto st = r.solver->stats();
    P.leaves = st.leaves;
    P.links = st.links;
    P.budgetReached = (st.budgetReached ? 1 : 0) | (st.timeBudgetReached ? 2 : 0) |
                      (r.reflectanceBudgetReached ? 4 : 0) | r.phaseBudgetReached;
    P.solverBytes = st.memoryBytes;
    P.maxLinks = st.maxLinks;
    P.maxMemory = st.maxMemory;
}

/// Past the budget at the end: said on the terminal with where the time went, and flagged
/// (PreparedImage::kBudgetOverrun), for a mesh whose work without fallback is more than the
/// budget (a stair hall subdivided 4 times: 74 s of 60).
void reportOverrun(Relighting& r, const RelightOptions& o, Clock::time_point begun) {
    if (!(r.budget.seconds > 0)) return;
    const double spent = radiosity::secondsSince(r.budget.start);
    if (!(spent > r.budget.seconds * PreparedImage::kOverrunTolerance)) return;
    r.prepared.budgetReached |= PreparedImage::kBudgetOverrun;
    const double before = std::chrono::duration<double>(begun - r.budget.start).count();
    const PrepareTimes& t = r.prepared.times;
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "warning: %.1f s spent of --time-budget %g s (loading the scene %.1f s, the "
                  "hierarchy and item buffer %.1f s, the solve %.1f s, the responses %.1f s, the "
                  "vertex lighting %.1f s): the phases with a fallback took it, the rest grows "
                  "with the mesh's %d leaves",
                  spent, r.budget.seconds, before, t.itemBuffer, t.solve, t.responses,
                  t.vertexLighting, r.solver->stats().leaves);
    say(o, msg);
}

}  // namespace

std::unique_ptr<Relighting> prepareRelighting(SceneFile scene, const RelightOptions& o) {
    const auto begun = Clock::now();
    auto r = std::make_unique<Relighting>();
    r->budget = {o.budgetStart == Clock::time_point{} ? begun : o.budgetStart, o.timeBudget};
    r->scene = std::move(scene);
    r->directOptions = directLightOptions(o);
    checkEstimableLights(r->scene);  // before the long work: an "estimate" light off in the photo
    // Before the long work too: a mesh the machine cannot hold ends now, with what it needs.
    const std::string memory =
        checkPreparationMemory(r->scene.scene, r->scene.dir.string(), o.machineMemory);
    if (!memory.empty()) say(o, memory);
    // The steps of the header's list.
    readPhotoAndCastItems(*r, o);        // 1
    estimateLightsFromPhoto(*r, o);      // 2
    solveAndEstimateReflectance(*r, o);  // 3
    refineAlongPhotoShadows(*r, o);      // 3, §4.2
    lightLeafVertices(*r, o);            // 4
    lightPixels(*r, o);                  // 4b, Loscos et al. 1999 §4.1, when asked
    removeShadowsForDisplay(*r, o);      // 5, §4.3-4.4
    mapDisplay(*r, o);                   // 6
    mergeAllPhotos(*r, o);               // 6b, Loscos et al. 1999 Eq. (3), when asked
    derivePhotoPixels(r->prepared);      // what the per-pixel display's pooling reads
    reportOverrun(*r, o, begun);
    return r;
}

std::vector<Rgb> editRadiance(const SceneFile& scene, const EditFile& edit,
                              std::span<const Rgb> photoRadiance) {
    if (photoRadiance.size() != scene.nominalRadiance.size() ||
        scene.estimateRadiance.size() != scene.nominalRadiance.size())
        throw std::invalid_argument("editRadiance: " + std::to_string(photoRadiance.size()) +
                                    " photo radiances for " +
                                    std::to_string(scene.nominalRadiance.size()) + " lights");
    std::vector<Rgb> nominal = scene.nominalRadiance;
    for (size_t l = 0; l < nominal.size(); ++l)
        if (scene.estimateRadiance[l]) nominal[l] = photoRadiance[l];
    return editedRadiance(scene, edit, nominal);
}

void requireFiniteImage(const Image& image, const SceneFile& scene, const EditFile& edit,
                        std::span<const Rgb> radiance, const std::string& what) {
    size_t bad = 0;
    for (const float v : image.rgb) bad += std::isfinite(v) ? 0 : 1;
    if (bad == 0) return;
    const std::string count =
        std::to_string(bad) + " of its " + std::to_string(image.rgb.size()) + " values";
    // The radiances the edit sets, by key; a non-finite one counts as the brightest.
    std::string key;
    Rgb blamed;
    double brightest = -1;
    const auto consider = [&](const std::string& k, const Rgb& c) {
        const bool finite = std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
        const double value = finite ? c.maxComponent() : HUGE_VAL;
        if (value > brightest) {
            brightest = value;
            key = k;
            blamed = c;
        }
    };
    for (const auto& [name, change] : edit.lights) {
        const int l = scene.scene.findLight(name);
        if (l < 0 || static_cast<size_t>(l) >= radiance.size()) continue;
        consider(jsonio::child(jsonio::child("lights", name), change.scale ? "scale" : "radiance"),
                 radiance[static_cast<size_t>(l)]);
    }
    for (size_t i = 0; i < edit.addLights.size(); ++i)
        consider(jsonio::child(jsonio::element("add_lights", i), "radiance"),
                 edit.addLights[i].radiance);
    if (key.empty()) throw std::runtime_error(what + " is not finite (" + count + ")");
    char text[160];
    std::snprintf(text, sizeof text, "[%.6g, %.6g, %.6g]", blamed.r, blamed.g, blamed.b);
    jsonio::JsonReader(edit.file.string())
        .fail(key, what + " is not finite (" + count + "): the light's radiance " + text +
                       " is too large");
}

}  // namespace relight
