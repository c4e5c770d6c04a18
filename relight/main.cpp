// relight: the command line. Subcommands:
//   relight solve <scene_dir> [--epsilon E] [--report out.json] [-o radiosity.exr|png]
//   relight eval  <scene_dir> <edit_name> <image>
// Errors in the input print one clear line naming the file and line or key, exit code 2.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "radiosity/solver.h"
#include "relight/image.h"
#include "relight/item_buffer.h"
#include "relight/lighting_buffer.h"
#include "relight/metric.h"
#include "relight/reflectance.h"
#include "relight/scene_file.h"

namespace fs = std::filesystem;
using namespace relight;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

nlohmann::json rgbJson(const radiosity::Rgb& c) {
    return {c.r, c.g, c.b};
}

struct SolveArgs {
    std::string scene;
    double epsilon = 1e-3;
    double minArea = 0;
    int minRays = 4, maxRays = 16;
    int spp = 16;
    int reflectanceRounds = 12;
    bool photoReflectance = true;
    std::string report, output;
    double exposure = 0;
};

int runSolve(const SolveArgs& a) {
    const auto tAll = Clock::now();
    SceneFile sf = loadScene(a.scene);
    for (const auto& w : sf.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    radiosity::SolverOptions o;
    o.epsilon = a.epsilon;
    o.minArea = a.minArea;
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
        tLighting = since(t0);
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
        Image photo = readImage(ph.file, ph.encoding == PhotoSpec::Encoding::srgb);
        if (photo.width != sf.camera.width || photo.height != sf.camera.height) {
            throw InputError(ph.file.string() + ": photo is " + std::to_string(photo.width) + "x" +
                             std::to_string(photo.height) + " but the camera is " +
                             std::to_string(sf.camera.width) + "x" +
                             std::to_string(sf.camera.height));
        }
        needItems();
        solver.solve();
        needLighting();
        std::fprintf(stderr, "estimating reflectance from %s (%d rounds)\n", ph.file.c_str(),
                     a.reflectanceRounds);
        auto rep =
            estimatePolygonReflectance(solver, sf, items, lighting, photo, a.reflectanceRounds);
        tReflectance = since(t0);
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
        nlohmann::json j = {{"scene", a.scene},
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
                              {"total", since(tAll)}}},
                            {"sweeps", st.sweeps},
                            {"refine_rounds", st.refineRounds},
                            {"energy",
                             {{"emitted", rgbJson(st.emittedPower)},
                              {"absorbed", rgbJson(st.absorbedPower)},
                              {"radiosity_power", rgbJson(st.radiosityPower)}}},
                            {"reflectance", reflectanceJson}};
        const fs::path tmp =
            fs::path(a.report).parent_path() / (".tmp-" + fs::path(a.report).filename().string());
        {
            std::ofstream out(tmp);
            out << j.dump(2) << "\n";
            if (!out) throw std::runtime_error(a.report + ": cannot write report");
        }
        fs::rename(tmp, a.report);
        std::printf("wrote %s\n", a.report.c_str());
    }
    return 0;
}

int runEval(const std::string& sceneDir, const std::string& edit, const std::string& image,
            const std::string& errorMapFile) {
    const fs::path dir(sceneDir);
    const SceneFile sf = loadScene(dir);
    if (sf.photos.empty())
        throw InputError((dir / "scene.json").string() + ": key \"photos\": eval needs a photo");
    const fs::path photo = sf.photos.front().file;
    fs::path photoMask = photo;
    photoMask.replace_extension(".mask.png");
    Image R = readImage(image);
    Image T = readImage(dir / "truth" / (edit + ".exr"));
    Image P = readImage(photo, sf.photos.front().encoding == PhotoSpec::Encoding::srgb);
    int w = 0, h = 0, w2 = 0, h2 = 0;
    auto mT = readMask(dir / "truth" / (edit + ".mask.png"), w, h);
    auto mP = readMask(photoMask, w2, h2);
    if (R.width != T.width || R.height != T.height)
        throw InputError(image + ": image is " + std::to_string(R.width) + "x" +
                         std::to_string(R.height) + ", the truth is " + std::to_string(T.width) +
                         "x" + std::to_string(T.height));
    Image errorMap;
    const Score s = scoreImage(R, T, P, mT, mP, errorMapFile.empty() ? nullptr : &errorMap);
    Image identity = readImage(dir / "truth" / "identity.exr");
    auto mI = readMask(dir / "truth" / "identity.mask.png", w, h);
    const Score floor = scoreImage(P, identity, P, mI, mP);
    std::printf("rel_rmse %.4f\n", s.relRmse);
    if (s.hasChanged)
        std::printf("changed_rel_rmse %.4f (%d of %d blocks)\n", s.changedRelRmse, s.changedBlocks,
                    s.blocks);
    else
        std::printf("changed_rel_rmse undefined (no block changes)\n");
    std::printf("noise_floor %.4f\n", floor.relRmse);
    if (!errorMapFile.empty()) {
        writeImage(errorMapFile, errorMap);
        std::printf("wrote %s (%dx%d blocks, block RMS error / mean truth)\n", errorMapFile.c_str(),
                    errorMap.width, errorMap.height);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"relight: relight photographs of real rooms (Loscos, Drettakis & Robert 2000)"};
    app.require_subcommand(1);

    SolveArgs sa;
    auto* solve =
        app.add_subcommand("solve", "clustered hierarchical radiosity solution of a scene");
    solve->add_option("scene_dir", sa.scene, "scene folder holding scene.json")->required();
    solve->add_option("--epsilon", sa.epsilon, "BF refinement threshold, fraction of emitted power")
        ->check(CLI::PositiveNumber);
    solve
        ->add_option("--min-area", sa.minArea,
                     "smallest element area in m^2 (0: 2e-5 of the scene's area)")
        ->check(CLI::NonNegativeNumber);
    solve->add_option("--min-rays", sa.minRays, "visibility rays per link, first round")
        ->check(CLI::Range(1, 256));
    solve->add_option("--max-rays", sa.maxRays, "visibility rays per link in penumbra")
        ->check(CLI::Range(1, 256));
    solve->add_option("--spp", sa.spp, "camera samples per pixel for -o")
        ->check(CLI::Range(1, 1024));
    solve
        ->add_option("--reflectance-rounds", sa.reflectanceRounds,
                     "photo reflectance estimate/solve rounds")
        ->check(CLI::Range(0, 20));
    solve->add_flag("!--no-photo-reflectance", sa.photoReflectance,
                    "use scene.json reflectances instead of estimating them from the photo");
    solve->add_option("--report", sa.report, "write counts, times and energy balance as JSON");
    solve->add_option("-o,--output", sa.output,
                      "write the radiosity seen from the camera (radiance B/pi)");
    solve->add_option("--exposure", sa.exposure, "exposure in stops for 8-bit output");

    std::string evScene, evEdit, evImage;
    auto* eval =
        app.add_subcommand("eval", "score an image against a scene's ground truth (spec metric)");
    eval->add_option("scene_dir", evScene)->required();
    eval->add_option("edit_name", evEdit)->required();
    eval->add_option("image", evImage)->required();
    std::string evErrorMap;
    eval->add_option("--error-map", evErrorMap,
                     "write the per-block error relative to the mean truth (EXR, or PNG)");

    CLI11_PARSE(app, argc, argv);
    try {
        if (*solve) {
            if (sa.maxRays < sa.minRays) sa.maxRays = sa.minRays;
            return runSolve(sa);
        }
        if (*eval) return runEval(evScene, evEdit, evImage, evErrorMap);
    } catch (const InputError& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
