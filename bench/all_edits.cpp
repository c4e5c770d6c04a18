// Every edit of one scene from one preparation: `relight render --edit` prepares a large
// scene again in memory for each edit with virtual lights, objects or removals (their
// insertion needs the solver), which on the staircase is 300 s and 12 GB each. This
// prepares once with `relight render`'s defaults (per-pixel display), renders every edit of
// the scene that has a truth (light edits by superposition, the others through
// DynamicRelighting, as relight/cli/render.cpp does), and scores each with the format's
// metric (`relight eval`'s rel_rmse and changed_rel_rmse).
//
//   ./build/bench/all_edits <scene_dir> [--out DIR] [--cache FILE] [--only EDIT,EDIT...]
//                           [--narrow-sources]
// --out: the relit images, EDIT.exr; --cache: also writes the prepared cache there (for
// bench/light_shares); --only: these edits alone. Run large scenes under `flock
// /tmp/relight-heavy.lock`.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/io/prepared_cache.h"
#include "relight/io/scene_file.h"
#include "relight/prepared.h"
#include "relight/relighting.h"

namespace fs = std::filesystem;
using namespace relight;

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: %s <scene_dir> [--out DIR] [--cache FILE] [--only EDIT,...] "
                     "[--narrow-sources]\n",
                     argv[0]);
        return 2;
    }
    const fs::path dir = argv[1];
    fs::path out, cache;
    std::string only;  // ",a,b,": the edits to render, empty: all
    bool narrow = false;
    for (int i = 2; i < argc; ++i) {
        if (std::strcmp(argv[i], "--narrow-sources") == 0) {
            narrow = true;
            continue;
        }
        if (i + 1 >= argc) break;
        if (std::strcmp(argv[i], "--out") == 0) out = argv[i + 1];
        if (std::strcmp(argv[i], "--cache") == 0) cache = argv[i + 1];
        if (std::strcmp(argv[i], "--only") == 0) only.append(",").append(argv[i + 1]).append(",");
        ++i;
    }
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\n");
    if (!out.empty()) fs::create_directories(out);
    const SceneFile sf = loadScene(dir);
    RelightOptions o;  // relight render's defaults (relight/cli/commands.h)
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.pixelLight = true;
    o.narrowSources = narrow;
    o.progress = [](const std::string& m) { std::fprintf(stderr, "  %s\n", m.c_str()); };
    const auto t0 = std::chrono::steady_clock::now();
    auto r = prepareRelighting(sf, o);
    std::printf("prepare %.1f s: %s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                stepTimes(r->prepared.times).c_str());
    if (!cache.empty()) writePreparedCache(cache, r->prepared, preparationKey(sf, o));
    std::vector<std::string> edits;
    for (const auto& e : fs::directory_iterator(dir / "edits"))
        if (fs::exists(dir / "truth" / (e.path().stem().string() + ".exr")) &&
            (only.empty() ||
             only.find(std::string(",").append(e.path().stem().string()).append(",")) !=
                 std::string::npos))
            edits.push_back(e.path().stem().string());
    std::sort(edits.begin(), edits.end());
    const Image photo =
        readImage(sf.photos.front().file, sf.photos.front().encoding == PhotoSpec::Encoding::srgb);
    fs::path photoMask = sf.photos.front().file;
    photoMask.replace_extension(".mask.png");
    int w = 0, h = 0;
    const auto mP = readMask(photoMask, w, h);
    std::printf("%-22s %9s %9s %8s\n", "edit", "rel_rmse", "changed", "edit_s");
    for (const auto& name : edits) {
        const EditFile edit = loadEdit(dir / "edits" / (name + ".json"), sf);
        const auto radiance = editRadiance(sf, edit, r->prepared.photoRadiance);
        const auto e0 = std::chrono::steady_clock::now();
        Image img;
        if (edit.addLights.empty() && edit.addObjects.empty() && edit.removeObjects.empty()) {
            img = renderEdit(r->prepared, radiance, DisplayMode::pixel);
        } else {
            DynamicRelighting dyn(*r, radiance);
            for (const std::string& obj : edit.removeObjects) dyn.removeObject(obj);
            for (const VirtualLight& l : edit.addLights) dyn.addLight(l);
            for (const VirtualObject& obj : edit.addObjects) dyn.addObject(obj);
            img = dyn.render(DisplayMode::pixel);
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - e0).count();
        if (!out.empty()) writeImage(out / (name + ".exr"), img);
        const Image truth = readImage(dir / "truth" / (name + ".exr"));
        const auto mT = readMask(dir / "truth" / (name + ".mask.png"), w, h);
        const Score s = scoreImage(img, truth, photo, mT, mP);
        char changed[32] = "-";
        if (s.hasChanged) std::snprintf(changed, sizeof changed, "%.4f", s.changedRelRmse);
        std::printf("%-22s %9.4f %9s %8.3f\n", name.c_str(), s.relRmse, changed, seconds);
        std::fflush(stdout);
    }
    return 0;
}
