// relight render <scene_dir> [--edit edit.json] -o out.exr|out.png [--report r.json]
//                [--cache FILE | --no-cache] [--debug-views DIR] (and the preparation
//                options of prepare)
// With --debug-views the scene is prepared in memory (the views need the solver state,
// which the cache does not hold; the cache is still written) and the pipeline's
// intermediate images go to DIR (relight/display/debug_views.h). The relit image is the same as
// without it. An edit with virtual lights or objects is also prepared in memory (their
// insertion needs the solver: relight/dynamic/dynamic_relighting.h); the views then show the
// real lights' part of the edit.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "relight/cli/commands.h"
#include "relight/cli/util.h"
#include "relight/display/debug_views.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

namespace relight::cli {

int runRender(const RenderArgs& a) {
    const auto tAll = Clock::now();
    const RelightOptions o = a.prep.relightOptions();
    std::fprintf(stderr, "relight render %s\n", a.scene.c_str());
    // The edit is read (and checked against the scene) before the long preparation, so a
    // bad edit fails at once.
    const SceneFile sf = loadScene(a.scene);
    EditFile edit;
    if (!a.edit.empty()) {
        edit = loadEdit(a.edit, sf);
        requireRenderable(edit);
    }
    // A folder that cannot be made fails at once too, not after the preparation.
    if (!a.debugViews.empty()) createDebugViewsFolder(a.debugViews);
    std::unique_ptr<Relighting> full;
    const bool virtualParts = !edit.addLights.empty() || !edit.addObjects.empty();
    const PreparedState s = loadOrPrepare(sf, o, a.cache, /*writeMustSucceed=*/false,
                                          a.debugViews.empty() && !virtualParts ? nullptr : &full);
    const PreparedImage& p = s.image;
    const double tPrepare = s.seconds;
    // The PreparedImage's photo radiance holds the estimates of "estimate" lights.
    const auto radiance = editRadiance(sf, edit, p.photoRadiance);
    double tViews = 0;
    size_t viewFiles = 0;
    auto t0 = Clock::now();
    if (full && !a.debugViews.empty()) {
        viewFiles = writeDebugViews(*full, radiance, a.debugViews).size();
        tViews = secondsSince(t0);
    }
    t0 = Clock::now();
    Image img;
    nlohmann::json virtualJson = nlohmann::json::array();
    if (virtualParts) {
        DynamicRelighting dyn(*full, radiance);
        const auto note = [&](const std::string& kind, const std::string& name) {
            const FrameTimes& ft = dyn.times();
            const radiosity::DynamicUpdate& u = dyn.lastUpdate();
            std::printf("inserted %s %s: %d links cut, %d new, %d reactivated, %.4f s\n",
                        kind.c_str(), name.c_str(), u.linksCut, u.linksNew, u.linksReactivated,
                        ft.total());
            virtualJson.push_back({{"kind", kind},
                                   {"name", name},
                                   {"links_cut", u.linksCut},
                                   {"links_new", u.linksNew},
                                   {"links_reactivated", u.linksReactivated},
                                   {"shaft_tests", u.shaftTests},
                                   {"rays", u.rays},
                                   {"time_s",
                                    {{"shafts", ft.shafts},
                                     {"visibility", ft.visibility},
                                     {"links", ft.links},
                                     {"radiosity", ft.radiosity},
                                     {"vertices", ft.vertices}}}});
        };
        for (const VirtualLight& l : edit.addLights) {
            dyn.addLight(l);
            note("light", l.name);
        }
        for (const VirtualObject& obj : edit.addObjects) {
            dyn.addObject(obj);
            note("object", obj.name);
        }
        img = dyn.render();
    } else {
        img = renderEdit(p, radiance);
    }
    const double tEdit = secondsSince(t0);
    writeImage(a.output, img, a.exposure);
    std::printf("leaves %d, links %d, leaf vertices %zu\n", p.leaves, p.links, p.vertexCount());
    if (s.cache == "hit")
        std::printf("time: load cache %.3f s (its preparation took: %s); edit %.4f s\n", tPrepare,
                    stepTimes(p.times).c_str(), tEdit);
    else
        std::printf("time: prepare %.3f s (%s); edit %.4f s\n", tPrepare,
                    stepTimes(p.times).c_str(), tEdit);
    std::printf("wrote %s (%dx%d)\n", a.output.c_str(), img.width, img.height);
    if (s.written) std::printf("wrote cache %s\n", s.file.string().c_str());
    if (!a.debugViews.empty())
        std::printf("wrote debug views %s (%zu files, %.3f s)\n", a.debugViews.c_str(), viewFiles,
                    tViews);
    if (!a.report.empty()) {
        nlohmann::json lights = nlohmann::json::object();
        for (size_t l = 0; l < radiance.size(); ++l)
            lights[sf.scene.lights[l].name] = rgbJson(radiance[l]);
        const nlohmann::json views =
            a.debugViews.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.debugViews);
        const nlohmann::json j = {{"scene", a.scene},
                                  {"edit", a.edit},
                                  {"output", a.output},
                                  {"epsilon", a.prep.epsilon},
                                  {"shadow_refinement", a.prep.shadowRefinement},
                                  {"shadow_removal", a.prep.shadowRemoval},
                                  {"cache", s.cache},
                                  {"cache_file", s.file.empty() ? nlohmann::json(nullptr)
                                                                : nlohmann::json(s.file.string())},
                                  {"debug_views", views},
                                  {"leaves", p.leaves},
                                  {"links", p.links},
                                  {"budget",
                                   {{"reached", p.budgetReached != 0},
                                    {"solver_mib", p.solverBytes / 1048576.0},
                                    {"max_links", p.maxLinks},
                                    {"max_memory_mib", p.maxMemory / 1048576.0}}},
                                  {"leaf_vertices", p.vertexCount()},
                                  {"lights", lights},
                                  {"virtual", virtualJson},
                                  {"time_s",
                                   {{"item_buffer", p.times.itemBuffer},
                                    {"solve", p.times.solve},
                                    {"reflectance", p.times.reflectance},
                                    {"refinement", p.times.refinement},
                                    {"responses", p.times.responses},
                                    {"vertex_lighting", p.times.vertexLighting},
                                    {"shadow_removal", p.times.shadowRemoval},
                                    {"display_map", p.times.displayMap},
                                    {"prepare", tPrepare},  // or the cache's loading
                                    {"edit", tEdit},
                                    {"debug_views", tViews},
                                    {"total", secondsSince(tAll)}}}};
        writeJsonAtomic(a.report, j);
        std::printf("wrote %s\n", a.report.c_str());
    }
    return 0;
}

}  // namespace relight::cli
