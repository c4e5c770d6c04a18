// relight render <scene_dir> [--edit edit.json] -o out.exr|out.png [--report r.json]
#include <cstdio>
#include <filesystem>

#include "relight/cli/commands.h"
#include "relight/cli/util.h"
#include "relight/edit_file.h"
#include "relight/image.h"
#include "relight/relighting.h"

namespace relight::cli {

int runRender(const RenderArgs& a) {
    const auto tAll = Clock::now();
    RelightOptions o;
    o.epsilon = a.epsilon;
    o.spp = a.spp;
    o.progress = [](const std::string& m) { std::fprintf(stderr, "  %s\n", m.c_str()); };
    std::fprintf(stderr, "relight render %s\n", a.scene.c_str());
    // The edit is read (and checked against the scene) before the long preparation, so a
    // bad edit fails at once.
    SceneFile sf = loadScene(a.scene);
    EditFile edit;
    if (!a.edit.empty()) {
        edit = loadEdit(a.edit, sf);
        requireLightsOnly(edit);
    }
    auto t0 = Clock::now();
    const auto r = prepareRelighting(std::move(sf), o);
    const double tPrepare = since(t0);
    const auto radiance = editRadiance(r->scene, edit);
    t0 = Clock::now();
    const Image img = renderEdit(r->prepared, radiance);
    const double tEdit = since(t0);
    writeImage(a.output, img, a.exposure);
    const auto st = r->solver->stats();
    std::printf("leaves %d, links %d, leaf vertices %zu\n", st.leaves, st.links,
                r->mesh->vertices().size());
    std::printf(
        "time: prepare %.3f s (item buffer %.3f, solve %.3f, reflectance %.3f, responses %.3f, "
        "vertex lighting %.3f, display map %.3f); edit %.4f s\n",
        tPrepare, r->prepared.times.itemBuffer, r->prepared.times.solve, r->prepared.times.reflectance, r->prepared.times.responses,
        r->prepared.times.vertexLighting, r->prepared.times.displayMap, tEdit);
    std::printf("wrote %s (%dx%d)\n", a.output.c_str(), img.width, img.height);
    if (!a.report.empty()) {
        nlohmann::json lights = nlohmann::json::object();
        for (size_t l = 0; l < radiance.size(); ++l)
            lights[r->scene.scene.lights[l].name] = rgbJson(radiance[l]);
        const nlohmann::json j = {{"scene", a.scene},
                                  {"edit", a.edit},
                                  {"output", a.output},
                                  {"epsilon", a.epsilon},
                                  {"leaves", st.leaves},
                                  {"links", st.links},
                                  {"leaf_vertices", r->mesh->vertices().size()},
                                  {"lights", lights},
                                  {"time_s",
                                   {{"item_buffer", r->prepared.times.itemBuffer},
                                    {"solve", r->prepared.times.solve},
                                    {"reflectance", r->prepared.times.reflectance},
                                    {"responses", r->prepared.times.responses},
                                    {"vertex_lighting", r->prepared.times.vertexLighting},
                                    {"display_map", r->prepared.times.displayMap},
                                    {"prepare", tPrepare},
                                    {"edit", tEdit},
                                    {"total", since(tAll)}}}};
        writeJsonAtomic(a.report, j);
        std::printf("wrote %s\n", a.report.c_str());
    }
    return 0;
}

}  // namespace relight::cli
