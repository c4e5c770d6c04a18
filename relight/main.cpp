// relight: the command line. Subcommands (relight/cli/):
//   relight solve   <scene_dir> [--epsilon E] [--report out.json] [-o radiosity.exr|png]
//   relight prepare <scene_dir> [preparation options] [--cache FILE] [--force]
//   relight render  <scene_dir> [--edit edit.json] -o out.exr|png [--report r.json]
//                   [preparation options] [--cache FILE | --no-cache] [--debug-views DIR]
//                   [--display ratio|confidence|pixel]
//   preparation options: --epsilon E, --spp N, --no-refinement, --no-shadow-removal,
//                        --max-links N, --max-memory MiB, --time-budget S, --display-pixels P,
//                        --no-pixel-light, --all-photos
//   relight eval    <scene_dir> <edit_name> <image> [--error-map file]
// Errors print one clear line naming the file (and the line or key); the exit code says
// which kind (relight/errors.h): 2 the input is wrong (the command line's options too), 3
// an output cannot be written, 1 anything else.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "relight/cli/commands.h"
#include "relight/cli/validators.h"
#include "relight/errors.h"

using namespace relight;
using cli::finiteNumber;
using cli::Sign;

namespace {

/// The budget options, the same for `solve`, `prepare` and `render`.
void addBudgetOptions(CLI::App* app, size_t& maxLinks, double& maxMemoryMB, double& timeBudget) {
    app->add_option("--time-budget", timeBudget,
                    "seconds the preparation may take: the refinement stops at half of it, "
                    "its largest errors refined first (0: no limit)")
        ->capture_default_str()
        ->check(finiteNumber(Sign::kNonNegative));
    app->add_option("--max-links", maxLinks,
                    "refinement budget in links (default: what fits in --max-memory)")
        ->check(cli::wholeNumber());
    app->add_option("--max-memory", maxMemoryMB,
                    "refinement budget in MiB of nodes and links (default: 40 % of RAM)")
        ->check(finiteNumber(Sign::kNonNegative));
}

/// The options of the preparation, the same for `prepare` and `render`.
void addPrepareOptions(CLI::App* app, cli::PrepareOptionArgs& p) {
    // The default shown is the pipeline's, finer than solve's (radiosity/defaults.h).
    app->add_option("--epsilon", p.epsilon, "BF refinement threshold")
        ->capture_default_str()
        ->check(finiteNumber(Sign::kPositive));
    app->add_option("--dark-floor", p.darkFloor,
                    "lowest factor on the refinement threshold of a receiver darker than the "
                    "mean radiosity (1: the plain BF criterion)")
        ->capture_default_str()
        ->check(CLI::Range(1e-3, 1.0));
    addBudgetOptions(app, p.maxLinks, p.maxMemoryMB, p.timeBudget);
    app->add_option("--spp", p.spp, "camera samples per pixel")->check(CLI::Range(1, 1024));
    app->add_flag("!--no-refinement", p.shadowRefinement,
                  "skip the texture-based refinement of shadow boundaries (§4.2)");
    app->add_flag("!--no-shadow-removal", p.shadowRemoval,
                  "skip real-shadow removal (§4.3-4.4): the 1997 method, D = B of the photo");
    app->add_option("--display-pixels", p.displayPixels,
                    "display pieces: leaves are split until a piece covers fewer photo pixels "
                    "than this (0: leaf corners only)")
        ->check(finiteNumber(Sign::kNonNegative));
    app->add_flag("--pixel-light,!--no-pixel-light", p.pixelLight,
                  "measure the direct light per pixel too (default), for render --display "
                  "pixel; --no-pixel-light for the vertex displays only (less time and "
                  "memory on large photos)");
    app->add_flag("--all-photos", p.allPhotos,
                  "read the light the first photo did not hold with the reflectance merged "
                  "from all of the scene's photos (Loscos et al. 1999, Eq. (3); with the "
                  "per-pixel light)");
}

CLI::App* addSolveCommand(CLI::App& app, cli::SolveArgs& sa) {
    auto* solve =
        app.add_subcommand("solve", "clustered hierarchical radiosity solution of a scene");
    solve->add_option("scene_dir", sa.scene, "scene folder holding scene.json")->required();
    solve->add_option("--epsilon", sa.epsilon, "BF refinement threshold, fraction of emitted power")
        ->capture_default_str()
        ->check(finiteNumber(Sign::kPositive));
    solve
        ->add_option("--min-area", sa.minArea,
                     "smallest element area in m^2 (0: 2e-5 of the scene's area)")
        ->check(finiteNumber(Sign::kNonNegative));
    addBudgetOptions(solve, sa.maxLinks, sa.maxMemoryMB, sa.timeBudget);
    solve->add_option("--min-rays", sa.minRays, "visibility rays per link, first round")
        ->capture_default_str()
        ->check(CLI::Range(1, 256));
    solve->add_option("--max-rays", sa.maxRays, "visibility rays per link in penumbra")
        ->capture_default_str()
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
    solve->add_option("--exposure", sa.exposure, "exposure in stops for 8-bit output")
        ->check(finiteNumber(Sign::kAny));
    return solve;
}

struct EvalArgs {
    std::string scene, edit, image, errorMap;
};

CLI::App* addEvalCommand(CLI::App& app, EvalArgs& ea) {
    auto* eval =
        app.add_subcommand("eval", "score an image against a scene's ground truth (spec metric)");
    eval->add_option("scene_dir", ea.scene)->required();
    eval->add_option("edit_name", ea.edit)->required();
    eval->add_option("image", ea.image)->required();
    eval->add_option("--error-map", ea.errorMap,
                     "write the per-block error relative to the mean truth (EXR, or PNG)");
    return eval;
}

CLI::App* addRenderCommand(CLI::App& app, cli::RenderArgs& ra) {
    auto* render = app.add_subcommand("render", "relight the scene's photo for an edit");
    render->add_option("scene_dir", ra.scene, "scene folder holding scene.json")->required();
    render->add_option("--edit", ra.edit, "relight-edit/1 JSON file (none: the photo's lights)");
    render->add_option("-o,--output", ra.output, "relit photo: .exr linear, .png sRGB")->required();
    render->add_option("--report", ra.report, "write counts and times as JSON");
    addPrepareOptions(render, ra.prep);
    render->add_option("--exposure", ra.exposure, "exposure in stops for 8-bit output")
        ->check(finiteNumber(Sign::kAny));
    render
        ->add_option("--display", ra.display,
                     "ratio: T B/D everywhere (Loscos et al. 2000); confidence: the light an "
                     "edit adds (lamps off in the photo, virtual parts) as the model's "
                     "rho B / pi where the photo's lamps did not light a point (Loscos et al. "
                     "1999's confidence); pixel: T H/H_photo with the direct light per pixel "
                     "(Loscos et al. 1999; prepares with --pixel-light)")
        ->capture_default_str()
        ->check(CLI::IsMember({"ratio", "confidence", "pixel"}));
    auto* renderCache =
        render->add_option("--cache", ra.cache.file,
                           "prepared-state cache (default <scene_dir>/.relight/prepared.bin)");
    render->add_flag("!--no-cache", ra.cache.use, "prepare without reading or writing a cache")
        ->excludes(renderCache);
    render->add_option("--debug-views", ra.debugViews,
                       "write the pipeline's intermediate images (B, D, textures, mesh, shadow "
                       "frontier) and an index.json into this folder");
    return render;
}

CLI::App* addPrepareCommand(CLI::App& app, cli::PrepareArgs& pa) {
    auto* prepare = app.add_subcommand(
        "prepare", "prepare a scene for rendering once and cache the prepared state on disk");
    prepare->add_option("scene_dir", pa.scene, "scene folder holding scene.json")->required();
    addPrepareOptions(prepare, pa.prep);
    prepare->add_option("--cache", pa.cache.file,
                        "where to write it (default <scene_dir>/.relight/prepared.bin)");
    prepare->add_flag("--force", pa.cache.force, "prepare again even when the cache is valid");
    return prepare;
}

/// A command line CLI11 could not parse: --help (exit code 0) as CLI11 prints it. A bad
/// option is bad input like any other: one line and exit code 2, not CLI11's own codes (105
/// for a value that fails its check, 106 for a missing one, ...), which scripts could not
/// tell from a crash.
int parseFailure(CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
    if (e.get_exit_code() == 0) return app.exit(e);
    const auto given = app.get_subcommands();
    const std::string help = given.empty() ? "relight" : "relight " + given.front()->get_name();
    // A misspelt command is not one CLI11 knows, so it only says that one is required.
    const std::string first = argc > 1 ? argv[1] : "";
    if (given.empty() && !first.empty() && first[0] != '-')
        std::fprintf(stderr,
                     "error: unknown command \"%s\" (solve, prepare, render or eval); see "
                     "relight --help\n",
                     first.c_str());
    else
        std::fprintf(stderr, "error: %s; see %s --help\n", e.what(), help.c_str());
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"relight: relight photographs of real rooms (Loscos, Drettakis & Robert 2000)"};
    app.require_subcommand(1);
    cli::SolveArgs sa;
    EvalArgs ea;
    cli::RenderArgs ra;
    cli::PrepareArgs pa;
    const CLI::App* solve = addSolveCommand(app, sa);
    const CLI::App* eval = addEvalCommand(app, ea);
    const CLI::App* render = addRenderCommand(app, ra);
    const CLI::App* prepare = addPrepareCommand(app, pa);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return parseFailure(app, e, argc, argv);
    }
    try {
        if (*solve) {
            if (sa.maxRays < sa.minRays) sa.maxRays = sa.minRays;
            return cli::runSolve(sa);
        }
        if (*render) return cli::runRender(ra);
        if (*prepare) return cli::runPrepare(pa);
        if (*eval) return cli::runEval(ea.scene, ea.edit, ea.image, ea.errorMap);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return exitCode(e);
    }
    return 0;
}
