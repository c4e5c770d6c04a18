// The `relight` command's subcommands, one file each; main.cpp parses the arguments.
// Each returns the process exit code and throws InputError for bad input.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "radiosity/defaults.h"
#include "relight/io/colmap_import.h"
#include "relight/io/scene_file.h"
#include "relight/prepared.h"
#include "relight/relighting.h"

namespace relight::cli {

/// `relight solve`: clustered hierarchical radiosity of a scene.
struct SolveArgs {
    std::string scene;
    double epsilon = radiosity::kDefaultEpsilon;  ///< radiosity/defaults.h: coarser than prepare's
    double minArea = 0;
    size_t maxLinks = 0;     ///< refinement budget in links (0: from the memory budget)
    double maxMemoryMB = 0;  ///< refinement budget in MiB (0: 40 % of the machine's memory)
    /// Seconds the whole solve may take, from its start (0: none), split as the
    /// preparation's: half of the preparation's default, since a solve is the first look at
    /// a scene and the radiosity part of a preparation (RelightOptions::kSolveTimeBudget).
    double timeBudget = RelightOptions::kSolveTimeBudget;
    int minRays = radiosity::kDefaultMinRays, maxRays = radiosity::kDefaultMaxRays;
    int spp = 16;
    int reflectanceRounds = 12;
    bool photoReflectance = true;
    std::string report, output;
    double exposure = 0;
};

int runSolve(const SolveArgs& a);

/// `relight sky`: the scene's environment light fitted to its photo (or to --photo, a photo
/// of the same camera and lights), printed as an edit that sets its "sh9" (Wen et al. 2003,
/// §3.4).
struct SkyArgs {
    std::string scene, photo;
    int spp = 16;  ///< item-buffer samples per pixel (planSampling may take fewer)
};

int runSky(const SkyArgs& a);

/// `relight eval`: scores an image against a scene's ground truth (spec metric).
int runEval(const std::string& sceneDir, const std::string& edit, const std::string& image,
            const std::string& errorMapFile);

/// Where the prepared state comes from (`prepare`, `render`): the cache file (empty: the
/// default, <scene_dir>/.relight/prepared.bin), whether to use it at all, and whether to
/// prepare again even when it is valid.
struct CacheArgs {
    std::string file;
    bool use = true;
    bool force = false;
};

/// The preparation options that `prepare` and `render` share (part of the cache's key).
struct PrepareOptionArgs {
    double epsilon = RelightOptions{}.epsilon;
    double darkFloor = RelightOptions{}.darkFloor;
    double perLightOracle = RelightOptions{}.perLightOracle;
    bool narrowSources = RelightOptions{}.narrowSources;
    size_t maxLinks = 0;
    double maxMemoryMB = 0;
    double timeBudget = RelightOptions::kCommandTimeBudget;  ///< seconds (0: none)
    int spp = 16;
    bool shadowRefinement = true;
    bool shadowRemoval = true;
    double displayPixels = RelightOptions{}.displayPiecePixels;
    /// Measure the direct light per pixel too (the default display needs it; off with
    /// --no-pixel-light for the vertex displays only).
    bool pixelLight = true;
    /// Merge the reflectance of all of the scene's photos per pixel (default: the first).
    bool allPhotos = false;
    bool importance = false;
    /// Cut the per-pixel display's indirect rays when its share of the time budget is spent.
    bool pixelGatherCut = RelightOptions{}.pixelGatherCut;

    /// The pipeline's options, with progress lines on stderr. `budgetStart`: the command's
    /// start, taken before the scene is loaded, from which --time-budget counts
    /// (RelightOptions::budgetStart).
    RelightOptions relightOptions(radiosity::Clock::time_point budgetStart) const;
};

/// `relight render`: the relit photo for an edit.
struct RenderArgs {
    std::string scene, edit, output, report;
    PrepareOptionArgs prep;
    std::string debugViews;  ///< folder for the pipeline's intermediate images (empty: none)
    double exposure = 0;
    CacheArgs cache;
    /// DisplayMode (relight/prepared.h): the per-pixel display by default, the most accurate
    /// on every bundled scene's every edit (bench/RESULTS.md, 2026-11-25).
    std::string display = "pixel";
};
int runRender(const RenderArgs& a);

/// `relight prepare`: prepares a scene once and writes the prepared state's cache.
struct PrepareArgs {
    std::string scene;
    PrepareOptionArgs prep;
    CacheArgs cache;
};
int runPrepare(const PrepareArgs& a);

/// `relight import colmap`: a scene package from a COLMAP model (relight/io/colmap_import.h).
int runImportColmap(const ColmapImportOptions& options);

/// `relight export colmap`: a scene's camera as a COLMAP model of one PINHOLE camera and one
/// image, for COLMAP's tools (and the import's round trips).
struct ExportColmapArgs {
    std::string scene, output;
    std::string name;  ///< the image's NAME (default: the first photo's file name)
    bool binary = false;
};
int runExportColmap(const ExportColmapArgs& a);

/// The prepared state from the cache when it is valid, else prepared (with progress on
/// stderr) and written to the cache. Says on stdout which it was, and why it prepared.
struct PreparedState {
    PreparedImage image;
    std::string cache;           ///< for reports: "hit", "rebuilt: <why>" or "disabled"
    std::filesystem::path file;  ///< the cache file (empty when disabled)
    bool written = false;        ///< the cache was (re)written
    double seconds = 0;          ///< time to load or to prepare and write
};

/// `writeMustSucceed`: a cache that cannot be written is an error (prepare) rather than a
/// warning on stderr (render: rendering goes on without it).
/// `solverState`: when given, the whole prepared state is wanted (debug views), which the
/// cache does not hold: the scene is prepared whatever the cache, *solverState gets the
/// state and `image` a copy of its PreparedImage, and the cache is written as when stale.
/// `scene` by value: a caller that has no use for it after moves it in, and its polygons go
/// to the solver uncopied (prepareRelighting).
PreparedState loadOrPrepare(SceneFile scene, const RelightOptions& options, const CacheArgs& cache,
                            bool writeMustSucceed,
                            std::unique_ptr<Relighting>* solverState = nullptr);

}  // namespace relight::cli
