// relight solve <scene_dir> [--epsilon E] [--report out.json] [-o radiosity.exr|png]
#include "relight/cli/commands.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "radiosity/solver.h"
#include "relight/cli/util.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/emittance.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/reflectance.h"
#include "relight/relighting.h"

namespace relight::cli {

int runSolve(const SolveArgs& a) {
    const auto tAll = Clock::now();
    SceneFile sf = loadScene(a.scene);
    for (const auto& w : sf.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    radiosity::SolverOptions o;
    o.epsilon = a.epsilon;
    o.minArea = a.minArea;
    o.maxLinks = a.maxLinks;
    o.maxMemory = static_cast<size_t>(a.maxMemoryMB * 1048576.0);
    o.transfer.minRays = a.minRays;
    o.transfer.maxRays = a.maxRays;
    o.progress = [](const std::string& m) { std::fprintf(stderr, "  %s\n", m.c_str()); };
    std::fprintf(stderr, "relight solve %s: %zu polygons, %zu lights, epsilon %g\n",
                 a.scene.c_str(), sf.scene.polygons.size(), sf.scene.lights.size(), a.epsilon);
    radiosity::HierarchicalSolver solver(sf.scene, o);
    ItemBuffer items;
    bool haveItems = false;
    auto needItems = [&] {
        if (!haveItems)
            items = castItemBuffer(sf.camera, solver.scene(), solver.visibility(), a.spp);
        haveItems = true;
    };
    // Lights whose radiance is "estimate": estimated from the first photo before anything is
    // solved, as the preparation does (relight/pipeline/emittance.h).
    if (std::find(sf.estimateRadiance.begin(), sf.estimateRadiance.end(), true) !=
        sf.estimateRadiance.end()) {
        checkEstimableLights(sf);
        const Image photo = loadFirstPhoto(sf);
        needItems();
        const EmittanceReport rep = estimateEmittance(sf, solver.scene(), items, photo);
        for (const auto& w : rep.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
        for (const auto& line : rep.summary()) std::fprintf(stderr, "  %s\n", line.c_str());
        std::vector<radiosity::Rgb> radiance;
        for (const LightEmittance& l : rep.lights) radiance.push_back(l.radiance);
        solver.setLightRadiances(radiance);  // not solved yet: sets the emittance only
    }
    LightingBuffer lighting;
    bool haveLighting = false;
    double tLighting = 0;
    auto needLighting = [&] {
        if (haveLighting) return;
        const auto t0 = Clock::now();
        radiosity::DirectLightOptions dlo;
        dlo.minRays = a.minRays;
        dlo.maxRays = a.maxRays;
        lighting = computeLightingBuffer(items, solver, dlo);
        tLighting = secondsSince(t0);
        haveLighting = true;
        std::fprintf(stderr, "per-pixel lighting: %llu shadow rays, %zu gather points, %.3f s\n",
                     static_cast<unsigned long long>(lighting.rays), lighting.gatherPolygon.size(),
                     tLighting);
    };
    double tReflectance = 0;
    nlohmann::json reflectanceJson = nullptr;
    if (a.photoReflectance && !sf.photos.empty()) {
        const auto t0 = Clock::now();
        const PhotoSpec& ph = sf.photos.front();
        const Image photo = loadFirstPhoto(sf);
        needItems();
        solver.solve();
        needLighting();
        std::fprintf(stderr, "estimating reflectance from %s (%d rounds)\n", ph.file.c_str(),
                     a.reflectanceRounds);
        auto rep =
            estimatePolygonReflectance(solver, sf, items, lighting, photo, a.reflectanceRounds);
        tReflectance = secondsSince(t0);
        reflectanceJson = {{"rounds", rep.rounds},
                           {"polygons_seen", rep.polygonsSeen},
                           {"polygons_defaulted", rep.polygonsDefaulted},
                           {"seconds", tReflectance}};
    } else {
        solver.solve();
    }
    const radiosity::SolverStats st = solver.stats();
    std::printf("elements %d (leaves %d), clusters %d\n", st.elements, st.leaves, st.clusters);
    std::printf("links %d: visible %d, partial %d, invisible %d; passive %d\n", st.links,
                st.linksVisible, st.linksPartial, st.linksInvisible, st.passiveLinks);
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
                st.maxLinks, st.budgetReached ? ": REACHED, refinement stopped" : "");
    if (!a.output.empty()) {
        needItems();
        needLighting();
        updateIndirect(lighting, solver);
        Image img = renderRadiosity(items, lighting, solver.scene());
        writeImage(a.output, img, a.exposure);
        std::printf("wrote %s (%dx%d, %d samples per pixel)\n", a.output.c_str(), img.width,
                    img.height, items.spp);
    }
    if (!a.report.empty()) {
        nlohmann::json j = {
            {"scene", a.scene},
            {"epsilon", a.epsilon},
            {"min_area_m2", solver.minArea()},
            {"elements", st.elements},
            {"leaves", st.leaves},
            {"clusters", st.clusters},
            {"links",
             {{"total", st.links},
              {"visible", st.linksVisible},
              {"partial", st.linksPartial},
              {"invisible", st.linksInvisible},
              {"passive", st.passiveLinks}}},
            {"rays", st.rays},
            {"form_factors", st.formFactors},
            {"shafts", {{"tests", st.shaftTests}, {"empty", st.shaftEmpty}}},
            {"time_s",
             {{"build", st.timeBuild},
              {"refine_visibility", st.timeRefine},
              {"gather", st.timeGather},
              {"push_pull", st.timePushPull},
              {"reflectance_total", tReflectance},
              {"per_pixel_lighting", tLighting},
              {"total", secondsSince(tAll)}}},
            {"sweeps", st.sweeps},
            {"budget",
             {{"reached", st.budgetReached},
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
            {"reflectance", reflectanceJson}};
        writeJsonAtomic(a.report, j);
        std::printf("wrote %s\n", a.report.c_str());
    }
    return 0;
}

}  // namespace relight::cli
