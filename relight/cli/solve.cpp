// relight solve <scene_dir> [--epsilon E] [--report out.json] [-o radiosity.exr|png]
#include "relight/cli/commands.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "radiosity/deadline.h"
#include "radiosity/solver.h"
#include "relight/cli/util.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/emittance.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/reflectance.h"
#include "relight/pipeline/sky_estimate.h"
#include "relight/relighting.h"

namespace relight::cli {

namespace {

void progressLine(const std::string& m) {
    std::fprintf(stderr, "  %s\n", m.c_str());
}

radiosity::SolverOptions solverOptions(const SolveArgs& a, const radiosity::TimeBudget& budget) {
    radiosity::SolverOptions o;
    o.epsilon = a.epsilon;
    o.minArea = a.minArea;
    o.maxLinks = a.maxLinks;
    o.maxMemory = static_cast<size_t>(a.maxMemoryMB * 1048576.0);
    o.refineUntil = budget.until(RelightOptions::kRefineShare);
    o.transfer.minRays = a.minRays;
    o.transfer.maxRays = a.maxRays;
    o.progress = progressLine;
    return o;
}

/// What the solve reads through the camera, each made the first time it is needed (by the
/// photo's emittance or reflectance, or by -o): the item buffer, and the per-pixel lighting
/// of the solution at the time it is first asked for. As in a preparation, a large photo
/// takes fewer samples per pixel and its estimates a sub-grid of pixels (planSampling), so
/// that their cost does not grow with the photo's size; the -o image needs every pixel.
class CameraSamples {
  public:
    CameraSamples(const SolveArgs& a, const SceneFile& sf, radiosity::HierarchicalSolver& solver)
        : a_(a),
          sf_(sf),
          solver_(solver),
          plan_(planSampling(sf.camera.width, sf.camera.height, a.spp, kDefaultSampleBudget)) {}

    const ItemBuffer& items() {
        if (!haveItems_)
            items_ = castItemBuffer(sf_.camera, solver_.scene(), solver_.visibility(), plan_.spp);
        haveItems_ = true;
        return items_;
    }

    /// The lighting on the estimates' sub-grid of pixels.
    LightingBuffer& lighting() {
        if (!haveLighting_) lighting_ = measure(plan_.stride);
        haveLighting_ = true;
        return lighting_;
    }

    /// The same, by `deadline`: null when not even a coarse sub-grid could be measured by
    /// then. With a finite deadline a sub-grid kCoarse times coarser is measured first (1/16
    /// of the rays); from its time the finest stride whose predicted time (rays follow the
    /// pixels: stride^-2) fits in what is left is measured, else the coarse one is kept. The
    /// estimate then has fewer pixels per polygon instead of none: before, a budget that
    /// could not hold every pixel's rays kept the scene's reflectances (Cornell box,
    /// --time-budget 1: rel_rmse 0.645; bench/RESULTS.md 2026-11-28).
    const LightingBuffer* lightingUntil(Clock::time_point deadline) {
        if (haveLighting_) return &lighting_;
        if (deadline == Clock::time_point::max()) return &lighting();
        const int coarse = plan_.stride * kCoarse;
        LightingBuffer b;
        const auto t0 = Clock::now();
        if (!radiosity::runUntil(deadline, [&] { b = measure(coarse); })) {
            std::fprintf(stderr, "per-pixel lighting given up at the deadline\n");
            return nullptr;
        }
        const double left = std::chrono::duration<double>(deadline - Clock::now()).count();
        const int stride = finestStrideWithin(secondsSince(t0), coarse, plan_.stride, left);
        if (stride < coarse) {
            LightingBuffer fine;
            if (radiosity::runUntil(deadline, [&] { fine = measure(stride); }))
                b = std::move(fine);
            else
                std::fprintf(stderr, "per-pixel lighting: stride %d given up, %d kept\n", stride,
                             coarse);
        }
        lighting_ = std::move(b);
        haveLighting_ = true;
        return &lighting_;
    }

    /// The lighting of every pixel, for the -o image.
    LightingBuffer& imageLighting() {
        // The estimates' lighting serves when it has every pixel (a coarser sub-grid may
        // have been measured for a short --time-budget).
        if (plan_.stride == 1 && (!haveLighting_ || lighting_.stride == 1)) return lighting();
        if (!haveImageLighting_) imageLighting_ = measure(1);
        haveImageLighting_ = true;
        return imageLighting_;
    }

    /// Seconds the per-pixel lighting took (0 when it was not needed).
    double lightingSeconds() const { return seconds_; }

  private:
    LightingBuffer measure(int stride) {
        const auto t0 = Clock::now();
        radiosity::DirectLightOptions dlo;
        // Every shadow ray of a sample where the links' shafts are not clear, not a first
        // round of minRays that stops when they agree: a sample whose rays all agree by
        // chance in a penumbra would read 0 or 1, and the pixel's mean of such samples is
        // biased towards a sharper shadow (Cornell box 0.0273 -> 0.0244 at epsilon 1e-4,
        // bench/RESULTS.md 2026-11-27 (sixth session)).
        dlo.minRays = a_.maxRays;
        dlo.maxRays = a_.maxRays;
        LightingBuffer b = computeLightingBuffer(items(), solver_, dlo, stride);
        const double s = secondsSince(t0);
        seconds_ += s;
        std::fprintf(stderr,
                     "per-pixel lighting (pixel stride %d): %llu shadow rays, %zu gather points, "
                     "%.3f s\n",
                     stride, static_cast<unsigned long long>(b.rays), b.gatherPolygon.size(), s);
        return b;
    }

    const SolveArgs& a_;
    const SceneFile& sf_;
    radiosity::HierarchicalSolver& solver_;
    SamplingPlan plan_;
    ItemBuffer items_;
    bool haveItems_ = false;
    LightingBuffer lighting_, imageLighting_;
    bool haveLighting_ = false, haveImageLighting_ = false;
    double seconds_ = 0;
    static constexpr int kCoarse = 4;
};

/// Lights whose radiance is "estimate": estimated from the first photo before anything is
/// solved, as the preparation does (relight/pipeline/emittance.h).
void estimateLightRadiances(SceneFile& sf, radiosity::HierarchicalSolver& solver,
                            CameraSamples& camera) {
    checkEstimableLights(sf);
    const Image photo = loadFirstPhoto(sf);
    const EmittanceReport rep = estimateEmittance(sf, solver.scene(), camera.items(), photo);
    for (const auto& w : rep.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (const auto& line : rep.summary()) std::fprintf(stderr, "  %s\n", line.c_str());
    std::vector<radiosity::Rgb> radiance;
    for (const LightEmittance& l : rep.lights) radiance.push_back(l.radiance);
    solver.setLightRadiances(radiance);  // not solved yet: sets the emittance only
    if (!hasSkyEstimate(sf)) return;
    // Then the sun and sky "estimate" (relight/pipeline/sky_estimate.h), the quads known.
    for (size_t l = 0; l < radiance.size(); ++l) sf.scene.lights[l].radiance = radiance[l];
    SkyEstimateOptions so;
    so.progress = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    const SkyEstimateReport sky = estimateSkyFromPhoto(sf, solver, camera.items(), photo, so);
    for (const auto& w : sky.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (const auto& line : sky.summary()) std::fprintf(stderr, "  %s\n", line.c_str());
}

/// The reflectance estimated from the photo, for the report.
struct ReflectanceEstimate {
    double seconds = 0;
    nlohmann::json report = nullptr;  ///< null when not estimated
};

/// Solves; with --photo-reflectance (the default) and a photo, then estimates the polygons'
/// reflectance from it, solving again in rounds.
ReflectanceEstimate solveScene(const SolveArgs& a, const SceneFile& sf,
                               radiosity::HierarchicalSolver& solver, CameraSamples& camera,
                               const radiosity::TimeBudget& budget) {
    if (!a.photoReflectance || sf.photos.empty()) {
        solver.solve();
        return {};
    }
    const auto t0 = Clock::now();
    const PhotoSpec& ph = sf.photos.front();
    const Image photo = loadFirstPhoto(sf);
    solver.solve();
    std::fprintf(stderr, "estimating reflectance from %s (%d rounds)\n", ph.file.c_str(),
                 a.reflectanceRounds);
    const double share = RelightOptions::kRefineShare + RelightOptions::kReflectanceShare;
    ReflectanceReport rep;
    rep.skipped = true;
    // Already past the estimate's share (a large mesh on a loaded machine: the stair hall at
    // load 8 reached it during the refinement), the per-pixel lighting it would need is not
    // measured either: 7 s there.
    // The lighting is part of the set-up: given up with it at the share's end (3 s of shadow
    // rays on the stair hall, measured and then thrown away when the rest did not fit).
    const LightingBuffer* lighting = nullptr;
    if (Clock::now() < budget.until(share)) {
        const ItemBuffer& items = camera.items();
        lighting = camera.lightingUntil(budget.until(share));
        if (lighting) {
            ReflectanceOptions ro;
            ro.rounds = a.reflectanceRounds;
            // Everything by the share's end: no round is owed (the smoke check of a
            // 262 k-triangle stair hall ran past its 40 s in rounds that had begun).
            ro.until = budget.until(share);
            ro.progress = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
            rep = estimatePolygonReflectance(solver, sf, items, *lighting, photo, ro);
        }
    }
    if (rep.skipped || rep.rounds == 0)
        std::fprintf(stderr,
                     "warning: the reflectance was not estimated: %s did not fit before %.0f %% "
                     "of --time-budget; the scene's reflectances are kept (a larger "
                     "--time-budget estimates it)\n",
                     rep.skipped ? "its set-up" : "no round", 100 * share);
    else
        std::fprintf(stderr, "  %d reflectance round(s)%s\n", rep.rounds,
                     rep.budgetReached ? ": their share of --time-budget was spent, stopped "
                                         "after a complete round"
                                       : "");
    ReflectanceEstimate r;
    r.seconds = secondsSince(t0);
    // Per object, the area-weighted mean of its polygons' reflectances (emitting faces left
    // out): what a user checks an estimate against.
    const radiosity::Scene& scene = solver.scene();
    std::vector<radiosity::Rgb> rho;
    for (const radiosity::Polygon& p : scene.polygons) rho.push_back(p.rho);
    const ObjectMeans means =
        objectMeans(scene, rho, [&](int p) { return scene.polygons[p].light < 0; });
    nlohmann::json objects = nlohmann::json::object();
    for (size_t o = 0; o < means.rho.size(); ++o)
        if (means.area[o] > 0) objects[scene.objects[o]] = rgbJson(means.rho[o]);
    r.report = {{"rounds", rep.rounds},
                {"budget_reached", rep.budgetReached},
                {"skipped", rep.skipped},
                {"polygons_seen", rep.polygonsSeen},
                {"polygons_defaulted", rep.polygonsDefaulted},
                {"objects", objects},
                {"seconds", r.seconds}};
    return r;
}

void printStats(const radiosity::SolverStats& st) {
    std::printf("input polygons %d in %d face clusters; elements %d (leaves %d), clusters %d\n",
                st.polygons, st.faceClusters, st.elements, st.leaves, st.clusters);
    std::printf(
        "links %d: visible %d, partial %d, invisible %d; passive %d; %d clusters' "
        "self-interaction below the threshold, not refined\n",
        st.links, st.linksVisible, st.linksPartial, st.linksInvisible, st.passiveLinks,
        st.selfLinksDeferred);
    std::printf("rays %llu, form factors %llu, shafts %llu (empty %llu)\n",
                static_cast<unsigned long long>(st.rays),
                static_cast<unsigned long long>(st.formFactors),
                static_cast<unsigned long long>(st.shaftTests),
                static_cast<unsigned long long>(st.shaftEmpty));
    std::printf(
        "time: build %.3f s, refine+visibility %.3f s, gather %.3f s, push-pull %.3f s (%d sweeps, "
        "%d rounds)\n",
        st.timeBuild, st.timeRefine, st.timeGather, st.timePushPull, st.sweeps, st.refineRounds);
    const double emitted = st.emittedPower.average();
    std::printf("energy: emitted %.4g, absorbed %.4g (%.1f %%), radiosity power %.4g\n", emitted,
                st.absorbedPower.average(),
                emitted > 0 ? 100 * st.absorbedPower.average() / emitted : 0.0,
                st.radiosityPower.average());
    std::printf("energy bound: %d leaves scaled, largest form-factor sum %.3f\n", st.boundedLeaves,
                st.maxGather);
    std::printf("budget: %.1f of %.1f MiB, %zu of %zu links%s\n", st.memoryBytes / 1048576.0,
                st.maxMemory / 1048576.0, static_cast<size_t>(st.links + st.passiveLinks),
                st.maxLinks,
                st.timeBudgetReached ? ": time budget REACHED, refinement stopped"
                : st.budgetReached   ? ": REACHED, refinement stopped"
                                     : "");
}

/// -o: the radiosity seen from the camera.
/// The -o image's final gather casts visibility rays until this share of --time-budget has
/// passed; the points after it keep their links' mean visibility (a coarser but whole
/// image). Not a bound: on the stair hall the gather took 14 s with rays and 13.6 s
/// without, its time being in the near links of large elements that hold thousands of
/// links each, gathered per point (bench/RESULTS.md, 2026-11-27, sixth session).
constexpr double kImageRaysShare = 0.75;

void writeRadiosityImage(const SolveArgs& a, const radiosity::HierarchicalSolver& solver,
                         CameraSamples& camera, const radiosity::TimeBudget& budget) {
    const ItemBuffer& items = camera.items();
    LightingBuffer& lighting = camera.imageLighting();
    const auto t0 = Clock::now();
    updateIndirect(lighting, solver, progressLine, budget.until(kImageRaysShare));
    std::fprintf(stderr, "final gather of the image: %zu points, %.3f s\n",
                 lighting.gatherPolygon.size(), secondsSince(t0));
    Image img = renderRadiosity(items, lighting, solver.scene());
    writeImage(a.output, img, a.exposure);
    std::printf("wrote %s (%dx%d, %d samples per pixel)\n", a.output.c_str(), img.width, img.height,
                items.spp);
}

nlohmann::json solveReport(const SolveArgs& a, const radiosity::HierarchicalSolver& solver,
                           const radiosity::SolverStats& st, const ReflectanceEstimate& reflectance,
                           double lightingSeconds, Clock::time_point tAll) {
    return {{"scene", a.scene},
            {"epsilon", a.epsilon},
            {"min_area_m2", solver.minArea()},
            {"elements", st.elements},
            {"leaves", st.leaves},
            {"input_polygons", st.polygons},
            {"face_clusters", st.faceClusters},
            {"clusters", st.clusters},
            {"links",
             {{"total", st.links},
              {"visible", st.linksVisible},
              {"partial", st.linksPartial},
              {"invisible", st.linksInvisible},
              {"passive", st.passiveLinks},
              {"self_deferred", st.selfLinksDeferred}}},
            {"rays", st.rays},
            {"form_factors", st.formFactors},
            {"shafts", {{"tests", st.shaftTests}, {"empty", st.shaftEmpty}}},
            {"time_s",
             {{"build", st.timeBuild},
              {"refine_visibility", st.timeRefine},
              {"gather", st.timeGather},
              {"push_pull", st.timePushPull},
              {"reflectance_total", reflectance.seconds},
              {"per_pixel_lighting", lightingSeconds},
              {"total", secondsSince(tAll)}}},
            {"sweeps", st.sweeps},
            {"budget",
             {{"reached", st.budgetReached},
              {"time_budget_reached", st.timeBudgetReached},
              {"time_budget_s", a.timeBudget},
              // Counted from the command's start: the refinement ends at this many
              // seconds, the reflectance rounds at the second.
              {"refine_ends_at_s", a.timeBudget * RelightOptions::kRefineShare},
              {"reflectance_ends_at_s",
               a.timeBudget * (RelightOptions::kRefineShare + RelightOptions::kReflectanceShare)},
              {"max_links", st.maxLinks},
              {"max_memory_bytes", st.maxMemory},
              {"memory_bytes", st.memoryBytes}}},
            {"energy_bound",
             {{"bounded_leaves", st.boundedLeaves}, {"max_form_factor_sum", st.maxGather}}},
            {"refine_rounds", st.refineRounds},
            {"energy",
             {{"emitted", rgbJson(st.emittedPower)},
              {"absorbed", rgbJson(st.absorbedPower)},
              {"radiosity_power", rgbJson(st.radiosityPower)}}},
            {"reflectance", reflectance.report}};
}

}  // namespace

int runSolve(const SolveArgs& a) {
    const auto tAll = Clock::now();
    // Counted from here: the loading of a large mesh is part of what the user waits for.
    const radiosity::TimeBudget budget{tAll, a.timeBudget};
    SceneFile sf = loadScene(a.scene);
    for (const auto& w : sf.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (const std::string c = contactSplitLine(sf); !c.empty())
        std::fprintf(stderr, "%s\n", c.c_str());
    std::fprintf(stderr, "relight solve %s: %zu polygons, %zu lights, epsilon %g\n",
                 a.scene.c_str(), sf.scene.polygons.size(), sf.scene.lights.size(), a.epsilon);
    radiosity::HierarchicalSolver solver(sf.scene, solverOptions(a, budget));
    for (const auto& w : lightReachWarnings(sf, solver.scene(), solver.visibility()))
        std::fprintf(stderr, "warning: %s\n", w.c_str());
    CameraSamples camera(a, sf, solver);
    // The threshold follows the power that reaches what the camera sees, as in a preparation
    // (solver.h, setCameraSeen): the sunlit outsides of a room's walls do not set it.
    solver.setCameraSeen(seenPolygons(camera.items(), solver.scene()));
    if (std::find(sf.estimateRadiance.begin(), sf.estimateRadiance.end(), true) !=
        sf.estimateRadiance.end())
        estimateLightRadiances(sf, solver, camera);
    const ReflectanceEstimate reflectance = solveScene(a, sf, solver, camera, budget);
    const radiosity::SolverStats st = solver.stats();
    printStats(st);
    if (!a.output.empty()) writeRadiosityImage(a, solver, camera, budget);
    if (!a.report.empty()) {
        writeJsonAtomic(a.report,
                        solveReport(a, solver, st, reflectance, camera.lightingSeconds(), tAll));
        std::printf("wrote %s\n", a.report.c_str());
    }
    return 0;
}

}  // namespace relight::cli
