// relight render <scene_dir> [--edit edit.json] -o out.exr|out.png [--report r.json]
//                [--cache FILE | --no-cache] [--debug-views DIR] (and the preparation
//                options of prepare)
// With --debug-views the scene is prepared in memory (the views need the solver state,
// which the cache does not hold; the cache is still written) and the pipeline's
// intermediate images go to DIR (relight/display/debug_views.h). The relit image is the same as
// without it. An edit with virtual lights or objects is also prepared in memory (their
// insertion needs the solver: relight/dynamic/dynamic_relighting.h); the views then show the
// real lights' part of the edit.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <utility>

#include "relight/cli/commands.h"

#include "radiosity/emitter.h"
#include "relight/cli/util.h"
#include "relight/display/debug_views.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/errors.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

namespace relight::cli {

namespace {

/// What the insertion of a virtual light or object did: a line on stdout, an entry of the
/// report's "virtual" list.
nlohmann::json insertionReport(const DynamicRelighting& dyn, const std::string& kind,
                               const std::string& name) {
    const FrameTimes& ft = dyn.times();
    const radiosity::DynamicUpdate& u = dyn.lastUpdate();
    if (kind == "removed object")
        std::printf(
            "removed object %s: %d links cut, %d pixels filled (%d from the model), %d around "
            "it relit, %.4f s (%.4f s of it the fill)\n",
            name.c_str(), u.linksCut, dyn.removedRegion().filled, dyn.removedRegion().modelled,
            dyn.removedRegion().ring, ft.total(), ft.fill);
    else
        std::printf(
            "inserted %s %s: %d links cut, %d new, %d reactivated, %d leaves split under its "
            "shadows, %.4f s\n",
            kind.c_str(), name.c_str(), u.linksCut, u.linksNew, u.linksReactivated, u.shadowSplits,
            ft.total());
    return {{"kind", kind},
            {"name", name},
            {"links_cut", u.linksCut},
            {"links_new", u.linksNew},
            {"links_reactivated", u.linksReactivated},
            {"shadow_splits", u.shadowSplits},
            {"shaft_tests", u.shaftTests},
            {"rays", u.rays},
            {"time_s",
             {{"shafts", ft.shafts},
              {"visibility", ft.visibility},
              {"links", ft.links},
              {"radiosity", ft.radiosity},
              {"vertices", ft.vertices},
              {"fill", ft.fill}}}};
}

/// The relit image of an edit with virtual lights or objects: each is inserted into the
/// prepared solver state `full` in turn, and reported in `report` (insertionReport).
Image renderWithVirtualParts(Relighting& full, const EditFile& edit,
                             std::span<const radiosity::Rgb> radiance, DisplayMode mode,
                             nlohmann::json& report, Image* editMesh) {
    const size_t preparedNodes = full.solver->hierarchy().nodes.size();
    DynamicRelighting dyn(full, radiance);
    // Real objects out first: the virtual parts then light and shade the room without them.
    for (const std::string& name : edit.removeObjects) {
        dyn.removeObject(name);
        report.push_back(insertionReport(dyn, "removed object", name));
    }
    // Moved lights (a sun turned, a lamp moved): off where they were, virtual where they went.
    for (const VirtualLight& l : movedLights(full.scene, edit)) {
        dyn.addLight(l);
        report.push_back(insertionReport(dyn, "moved light", l.name));
    }
    for (const VirtualLight& l : edit.addLights) {
        dyn.addLight(l);
        report.push_back(insertionReport(dyn, "light", l.name));
    }
    for (const VirtualObject& obj : edit.addObjects) {
        dyn.addObject(obj);
        report.push_back(insertionReport(dyn, "object", obj.name));
    }
    const radiosity::HierarchicalSolver& solver = *full.solver;
    for (const std::string& w : virtualLightReachWarnings(edit, solver.scene(), solver.visibility(),
                                                          static_cast<size_t>(dyn.realLights())))
        std::fprintf(stderr, "warning: %s\n", w.c_str());
    // The leaves as the insertions left them, before they are taken out again.
    if (editMesh) *editMesh = editMeshView(full, preparedNodes);
    return dyn.render(mode);
}

/// Seconds spent on each part of a render.
struct RenderTimes {
    double prepare = 0;  ///< preparing, or loading the cache
    double views = 0;    ///< the debug views
    double edit = 0;     ///< the relit image
};

void printSummary(const RenderArgs& a, const PreparedState& s, const Image& img,
                  const RenderTimes& t, size_t viewFiles) {
    const PreparedImage& p = s.image;
    std::printf("leaves %d, links %d, leaf vertices %zu\n", p.leaves, p.links, p.vertexCount());
    if (s.cache == "hit")
        std::printf("time: load cache %.3f s (its preparation took: %s); edit %.4f s\n", t.prepare,
                    stepTimes(p.times).c_str(), t.edit);
    else
        std::printf("time: prepare %.3f s (%s); edit %.4f s\n", t.prepare,
                    stepTimes(p.times).c_str(), t.edit);
    std::printf("wrote %s (%dx%d)\n", a.output.c_str(), img.width, img.height);
    if (s.written) std::printf("wrote cache %s\n", s.file.string().c_str());
    if (!a.debugViews.empty())
        std::printf("wrote debug views %s (%zu files, %.3f s)\n", a.debugViews.c_str(), viewFiles,
                    t.views);
}

nlohmann::json renderReport(const RenderArgs& a, const SceneFile& sf, const PreparedState& s,
                            std::span<const radiosity::Rgb> radiance,
                            const nlohmann::json& virtualParts, const RenderTimes& t,
                            Clock::time_point tAll) {
    const PreparedImage& p = s.image;
    nlohmann::json lights = nlohmann::json::object();
    for (size_t l = 0; l < radiance.size(); ++l)
        lights[sf.scene.lights[l].name] = rgbJson(radiance[l]);
    // The lights whose strength was "estimate", at their estimate (the photo's state):
    // a sky's 9 coefficients as "sh9" rows, a sun's "irradiance", a quad's "radiance".
    nlohmann::json estimated = nlohmann::json::object();
    for (size_t l = 0; l < sf.scene.lights.size() && l < p.photoRadiance.size(); ++l) {
        if (!sf.estimateRadiance[l]) continue;
        const radiosity::Light& light = sf.scene.lights[l];
        const radiosity::Rgb& v = p.photoRadiance[l];
        if (!light.emitter)
            estimated[light.name] = {{"radiance", rgbJson(v)}};
        else if (light.emitter->components() == 1)
            estimated[light.name] = {{"irradiance", rgbJson(v)}};
        else
            estimated[light.name]["sh9"].push_back(rgbJson(v));
    }
    const nlohmann::json views =
        a.debugViews.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.debugViews);
    return {
        {"scene", a.scene},
        {"edit", a.edit},
        {"output", a.output},
        {"epsilon", a.prep.epsilon},
        {"dark_floor", a.prep.darkFloor},
        {"per_light_oracle", a.prep.perLightOracle},
        {"narrow_sources", a.prep.narrowSources},
        {"shadow_refinement", a.prep.shadowRefinement},
        {"shadow_removal", a.prep.shadowRemoval},
        {"display", a.display},
        {"cache", s.cache},
        {"cache_file", s.file.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.file.string())},
        {"debug_views", views},
        {"leaves", p.leaves},
        {"links", p.links},
        {"budget",
         {{"reached", (p.budgetReached & 1) != 0},
          {"time_budget_reached", (p.budgetReached & 2) != 0},
          {"reflectance_budget_reached", (p.budgetReached & 4) != 0},
          {"shadow_refinement_budget_reached",
           (p.budgetReached & PreparedImage::kShadowRefinementBudget) != 0},
          {"vertex_gather_budget_reached", (p.budgetReached & PreparedImage::kGatherBudget) != 0},
          {"leaf_reflectance_skipped",
           (p.budgetReached & PreparedImage::kLeafReflectanceBudget) != 0},
          {"pixel_gather_budget_reached",
           (p.budgetReached & PreparedImage::kPixelGatherBudget) != 0},
          {"shadow_removal_skipped", (p.budgetReached & PreparedImage::kShadowRemovalBudget) != 0},
          {"overrun", (p.budgetReached & PreparedImage::kBudgetOverrun) != 0},
          {"shares_end_at",
           {{"refinement", RelightOptions::kRefineShare},
            {"reflectance", RelightOptions::kRefineShare + RelightOptions::kReflectanceShare},
            {"shadow_refinement", RelightOptions::kShadowRefinementEnds},
            {"vertex_gather", RelightOptions::kVertexGatherEnds},
            {"pixel_gather", RelightOptions::kPixelGatherEnds},
            {"shadow_removal", RelightOptions::kShadowRemovalEnds}}},
          {"time_budget_s", a.prep.timeBudget},
          {"solver_mib", p.solverBytes / 1048576.0},
          {"max_links", p.maxLinks},
          {"max_memory_mib", p.maxMemory / 1048576.0}}},
        {"leaf_vertices", p.vertexCount()},
        {"lights", lights},
        {"estimated", estimated},
        {"virtual", virtualParts},
        {"time_s",
         {{"item_buffer", p.times.itemBuffer},
          {"solve", p.times.solve},
          {"reflectance", p.times.reflectance},
          {"refinement", p.times.refinement},
          {"responses", p.times.responses},
          {"vertex_lighting", p.times.vertexLighting},
          {"shadow_removal", p.times.shadowRemoval},
          {"display_map", p.times.displayMap},
          {"prepare", t.prepare},  // or the cache's loading
          {"edit", t.edit},
          {"debug_views", t.views},
          {"total", secondsSince(tAll)}}}};
}

}  // namespace

int runRender(const RenderArgs& a) {
    const auto tAll = Clock::now();
    RelightOptions o = a.prep.relightOptions(tAll);  // the budget counts from the start
    const DisplayMode mode = parseDisplayMode(a.display);
    if (drawsPerPixel(mode)) o.pixelLight = true;
    std::fprintf(stderr, "relight render %s\n", a.scene.c_str());
    // The edit is read (and checked against the scene) before the long preparation, so a
    // bad edit fails at once.
    SceneFile loaded = loadScene(a.scene);
    EditFile edit;
    if (!a.edit.empty()) {
        edit = loadEdit(a.edit, loaded);
    }
    // The preparation takes the polygons (it moves them into the solver); render reads the
    // lights, the camera and the names after it, from a copy without them: one copy of a
    // large mesh in memory, not two.
    const SceneFile sf = copyWithoutPolygons(loaded);
    for (const std::string& w : edit.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    // A folder that cannot be made fails at once too, not after the preparation.
    if (!a.debugViews.empty()) createDebugViewsFolder(a.debugViews);
    std::unique_ptr<Relighting> full;
    const bool virtualParts = !edit.addLights.empty() || !edit.addObjects.empty() ||
                              !edit.removeObjects.empty() ||
                              std::any_of(edit.lights.begin(), edit.lights.end(),
                                          [](const auto& l) { return l.second.moves(); });
    const PreparedState s = loadOrPrepare(std::move(loaded), o, a.cache, /*writeMustSucceed=*/false,
                                          a.debugViews.empty() && !virtualParts ? nullptr : &full);
    RenderTimes t;
    t.prepare = s.seconds;
    // The PreparedImage's photo radiance holds the estimates of "estimate" lights.
    const auto radiance = editRadiance(sf, edit, s.image.photoRadiance);
    // The real lights' part of the edit (all of it without virtual parts), refused when not
    // finite before anything is written, the debug views (which show that part) included.
    auto t0 = Clock::now();
    Image img = renderEdit(s.image, radiance, mode);
    requireFiniteImage(img, sf, edit, radiance);
    t.edit = secondsSince(t0);
    nlohmann::json virtualJson = nlohmann::json::array();
    Image editMesh;
    if (virtualParts) {
        t0 = Clock::now();
        img = renderWithVirtualParts(*full, edit, radiance, mode, virtualJson,
                                     a.debugViews.empty() ? nullptr : &editMesh);
        requireFiniteImage(img, sf, edit, radiance);
        t.edit = secondsSince(t0);
    }
    // The views of the prepared state (the virtual parts are out of the solver again, which
    // is as prepared bit for bit), with the leaves as the edit left them.
    size_t viewFiles = 0;
    t0 = Clock::now();
    if (full && !a.debugViews.empty()) {
        viewFiles = writeDebugViews(*full, radiance, a.debugViews, &editMesh).size();
        t.views = secondsSince(t0);
    }
    writeImage(a.output, img, a.exposure);
    printSummary(a, s, img, t, viewFiles);
    if (!a.report.empty()) {
        writeJsonAtomic(a.report, renderReport(a, sf, s, radiance, virtualJson, t, tAll));
        std::printf("wrote %s\n", a.report.c_str());
    }
    return 0;
}

}  // namespace relight::cli
