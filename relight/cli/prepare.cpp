// relight prepare <scene_dir> [--epsilon E] [--spp N] [--no-refinement] [--no-shadow-removal]
//                 [--cache FILE] [--force]
// and the cache logic that render shares with it (loadOrPrepare).
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "relight/cli/commands.h"
#include "relight/cli/util.h"
#include "relight/io/prepared_cache.h"
#include "relight/relighting.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

/// A valid cache made from these inputs fits the scene; checked anyway, as the key could
/// only miss this by a hash collision.
std::string fitsScene(const PreparedImage& p, const SceneFile& sf) {
    if (p.photoRadiance.size() != sf.scene.lights.size())
        return "cache does not fit the scene: " + std::to_string(p.photoRadiance.size()) +
               " lights, the scene has " + std::to_string(sf.scene.lights.size());
    if (p.photo.width != sf.camera.width || p.photo.height != sf.camera.height)
        return "cache does not fit the scene: the photo's size differs from the camera's";
    return {};
}

}  // namespace

RelightOptions PrepareOptionArgs::relightOptions(Clock::time_point budgetStart) const {
    RelightOptions o;
    o.budgetStart = budgetStart;
    o.epsilon = epsilon;
    o.darkFloor = darkFloor;
    o.perLightOracle = perLightOracle;
    o.narrowSources = narrowSources;
    o.maxLinks = maxLinks;
    o.maxMemory = static_cast<size_t>(maxMemoryMB * 1048576.0);
    o.timeBudget = timeBudget;
    o.spp = spp;
    o.shadowRefinement = shadowRefinement;
    o.shadowRemoval = shadowRemoval;
    o.displayPiecePixels = displayPixels;
    o.pixelLight = pixelLight;
    o.mergePhotos = allPhotos;
    o.importance = importance;
    o.pixelGatherCut = pixelGatherCut;
    o.progress = [](const std::string& m) { std::fprintf(stderr, "  %s\n", m.c_str()); };
    return o;
}

PreparedState loadOrPrepare(SceneFile sf, const RelightOptions& o, const CacheArgs& c,
                            bool writeMustSucceed, std::unique_ptr<Relighting>* solverState) {
    PreparedState s;
    const auto t0 = Clock::now();
    auto prepare = [&] {
        // Last use of sf: its polygons go to the solver rather than being copied there.
        auto r = prepareRelighting(std::move(sf), o);
        if (!solverState) {
            s.image = std::move(r->prepared);
            return;
        }
        s.image = r->prepared;  // a copy: milliseconds next to the preparation
        *solverState = std::move(r);
    };
    if (!c.use) {
        prepare();
        s.cache = "disabled";
        s.seconds = secondsSince(t0);
        return s;
    }
    s.file = c.file.empty() ? defaultCachePath(sf.dir) : fs::path(c.file);
    const uint64_t key = preparationKey(sf, o);
    std::string why;
    if (solverState) {
        why = "the solver state is needed, which the cache does not hold";
    } else if (c.force) {
        why = "forced (--force)";
    } else if (auto p = readPreparedCache(s.file, key, &why)) {
        why = fitsScene(*p, sf);
        if (why.empty()) {
            s.image = std::move(*p);
            s.cache = "hit";
            s.seconds = secondsSince(t0);
            std::printf("using cache %s\n", s.file.string().c_str());
            std::fflush(stdout);
            return s;
        }
    }
    std::printf("%s; preparing\n", why.c_str());
    std::fflush(stdout);
    prepare();
    s.cache = "rebuilt: " + why;
    try {
        writePreparedCache(s.file, s.image, key);
        s.written = true;
    } catch (const std::exception& e) {
        if (writeMustSucceed) throw;
        std::fprintf(stderr, "warning: %s; going on without it\n", e.what());
    }
    s.seconds = secondsSince(t0);
    return s;
}

int runPrepare(const PrepareArgs& a) {
    // Taken before the scene is loaded: the budget counts from the command's start.
    const RelightOptions o = a.prep.relightOptions(Clock::now());
    std::fprintf(stderr, "relight prepare %s\n", a.scene.c_str());
    SceneFile sf = loadScene(a.scene);
    for (const auto& w : sf.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (const std::string c = contactSplitLine(sf); !c.empty())
        std::fprintf(stderr, "%s\n", c.c_str());
    CacheArgs cache = a.cache;
    cache.use = true;
    const PreparedState s = loadOrPrepare(std::move(sf), o, cache, /*writeMustSucceed=*/true);
    const PreparedImage& p = s.image;
    std::printf("leaves %d, links %d, leaf vertices %zu\n", p.leaves, p.links, p.vertexCount());
    std::printf("budget: %.1f of %.1f MiB, links within %llu%s\n", p.solverBytes / 1048576.0,
                p.maxMemory / 1048576.0, static_cast<unsigned long long>(p.maxLinks),
                (p.budgetReached & 2)   ? ": time budget REACHED, refinement stopped"
                : (p.budgetReached & 1) ? ": REACHED, refinement stopped"
                                        : "");
    if (p.budgetReached & 4)
        std::printf(
            "time budget: the reflectance rounds stopped before %.0f %% of --time-budget "
            "%g s had passed, after a complete round\n",
            100 * (RelightOptions::kRefineShare + RelightOptions::kReflectanceShare), o.timeBudget);
    for (const std::string& line : phaseBudgetLines(p.budgetReached, o.timeBudget))
        std::printf("time budget: %s\n", line.c_str());
    if (s.written)
        std::printf("time: prepare %.3f s (%s)\n", s.seconds, stepTimes(p.times).c_str());
    else
        std::printf("time: load %.3f s (its preparation took: %s)\n", s.seconds,
                    stepTimes(p.times).c_str());
    std::error_code ec;
    const auto bytes = fs::file_size(s.file, ec);
    if (s.written)
        std::printf("wrote cache %s (%.1f MB)\n", s.file.string().c_str(),
                    ec ? 0.0 : static_cast<double>(bytes) / 1e6);
    else
        std::printf("cache up to date: %s (--force prepares again)\n", s.file.string().c_str());
    return 0;
}

}  // namespace relight::cli
