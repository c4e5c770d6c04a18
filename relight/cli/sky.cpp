// relight sky <scene_dir> [--photo FILE]
// The sky of a photo as an edit (Wen, Liu & Huang 2003, §3.4: one photo's light put on
// another): the scene's environment light fitted to the photo (relight/pipeline/
// sky_estimate.h, whatever its scene.json "sh9" says), printed on stdout as a
// relight-edit/1 document that sets that light's "sh9"; the fit's summary on stderr.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "radiosity/emitter.h"
#include "relight/cli/commands.h"
#include "relight/cli/util.h"
#include "relight/errors.h"
#include "relight/pipeline/emittance.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/sky_estimate.h"

namespace relight::cli {

namespace {

/// Marks the scene's one environment light "estimate" (its components off until the fit);
/// InputError when the scene has none.
std::string markSkyEstimated(SceneFile& sf) {
    std::string name;
    for (size_t l = 0; l < sf.scene.lights.size(); ++l) {
        const radiosity::Light& light = sf.scene.lights[l];
        if (!light.emitter || light.emitter->components() != radiosity::kSh9Count) continue;
        name = light.name;
        sf.estimateRadiance[l] = true;
        sf.nominalRadiance[l] = {};
        sf.scene.lights[l].radiance = {};
    }
    if (name.empty())
        throw InputError((sf.dir / "scene.json").string() +
                         ": key \"lights\": no light of type \"environment\" to fit");
    return name;
}

nlohmann::json sh9Json(const radiosity::Sh9Rgb& L) {
    nlohmann::json rows = nlohmann::json::array();
    for (const radiosity::Rgb& c : L.c) rows.push_back(rgbJson(c));
    return rows;
}

}  // namespace

int runSky(const SkyArgs& a) {
    SceneFile sf = loadScene(a.scene);
    for (const auto& w : sf.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (!a.photo.empty()) {
        if (sf.photos.empty())
            throw InputError((sf.dir / "scene.json").string() +
                             ": key \"photos\": --photo needs the photo's lights_on");
        sf.photos.front().file = a.photo;  // the same camera, the first photo's lights
        bool known = false;
        sf.photos.front().encoding = encodingFromExtension(a.photo, known);
        if (!known) throw InputError(a.photo + ": cannot tell its encoding from its extension");
    }
    const std::string sky = markSkyEstimated(sf);
    checkEstimableLights(sf);
    const Image photo = loadFirstPhoto(sf);
    radiosity::HierarchicalSolver solver(sf.scene);
    const SamplingPlan plan =
        planSampling(sf.camera.width, sf.camera.height, a.spp, kDefaultSampleBudget);
    const ItemBuffer items =
        castItemBuffer(sf.camera, solver.scene(), solver.visibility(), plan.spp);
    // Quads of "estimate" radiance first, as the preparation does (their light is then known).
    const EmittanceReport rep = estimateEmittance(sf, solver.scene(), items, photo);
    for (size_t l = 0; l < rep.lights.size(); ++l)
        if (!sf.scene.lights[l].emitter) sf.scene.lights[l].radiance = rep.lights[l].radiance;
    std::vector<radiosity::Rgb> radiance;
    for (const radiosity::Light& l : sf.scene.lights) radiance.push_back(l.radiance);
    solver.setLightRadiances(radiance);
    SkyEstimateOptions so;
    so.stride = plan.stride;
    so.progress = [](const std::string& m) { std::fprintf(stderr, "%s\n", m.c_str()); };
    const SkyEstimateReport fit = estimateSkyFromPhoto(sf, solver, items, photo, so);
    for (const auto& w : fit.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    for (const auto& line : fit.summary()) std::fprintf(stderr, "  %s\n", line.c_str());
    const nlohmann::json edit = {{"format", "relight-edit/1"},
                                 {"lights", {{sky, {{"sh9", sh9Json(fit.sky)}}}}}};
    std::printf("%s\n", edit.dump(1).c_str());
    return 0;
}

}  // namespace relight::cli
