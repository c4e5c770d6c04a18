// relight: the command line. Subcommands (relight/cli/):
//   relight solve   <scene_dir> [--epsilon E] [--report out.json] [-o radiosity.exr|png]
//   relight prepare <scene_dir> [preparation options] [--cache FILE] [--force]
//   relight render  <scene_dir> [--edit edit.json] -o out.exr|png [--report r.json]
//                   [preparation options] [--cache FILE | --no-cache] [--debug-views DIR]
//                   [--display ratio|confidence|pixel|ratio-map|wen]
//   preparation options: --epsilon E, --spp N, --no-refinement, --no-shadow-removal,
//                        --max-links N, --max-memory MiB, --time-budget S, --display-pixels P,
//                        --no-pixel-light, --all-photos
//   relight eval    <scene_dir> <edit_name> <image> [--error-map file]
//   relight sky     <scene_dir> [--photo FILE] [--spp N]   (prints an edit's "sh9")
//   relight import colmap <sparse_dir> --image NAME --images DIR --mesh FILE
//                   [--lights FILE] [--objects FILE] [--lights-on A,B] -o SCENE_DIR
//   relight export colmap <scene_dir> -o SPARSE_DIR [--binary] [--name NAME]
// Errors print one clear line naming the file (and the line or key); the exit code says
// which kind (relight/errors.h): 2 the input is wrong (the command line's options too), 3
// an output cannot be written, 1 anything else.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

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
                    "seconds the solution may take from the command's start (the default "
                    "suits a 2-core laptop), split over its phases: the refinement stops when "
                    "half of it has passed, its largest errors refined first; the reflectance "
                    "rounds at 65 %, after a complete round; prepare and render: the "
                    "shadow-boundary refinement at 75 %, the vertices' gather at 83 %, the "
                    "per-pixel gather at 90 %, shadow removal at 100 %, each then taking a "
                    "coarser fallback it announces (0: no limit)")
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
    app->add_option("--per-light-oracle", p.perLightOracle,
                    "refine each light's own light to comparable relative accuracy: a link is "
                    "weighed by its source's light from each lamp alone, a lamp's weight raised "
                    "to all lamps' power, by at most this factor (0: off, the total light only)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 1e6));
    app->add_flag("--narrow-sources", p.narrowSources,
                  "a visible link from a cluster gathers from the part of it that faces the "
                  "receiver (a lamp's shade sends its outside's light, not its inside's)");
    addBudgetOptions(app, p.maxLinks, p.maxMemoryMB, p.timeBudget);
    app->add_option("--spp", p.spp, "camera samples per pixel")->check(CLI::Range(1, 1024));
    app->add_flag("!--no-refinement", p.shadowRefinement,
                  "skip the texture-based refinement of shadow boundaries (§4.2)");
    app->add_flag("--importance", p.importance,
                  "weigh the refinement by what the photo's camera sees and what lights it "
                  "(importance, Smits, Arvo & Salesin 1992)");
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
    app->add_flag("--pixel-gather-cut,!--no-pixel-gather-cut", p.pixelGatherCut,
                  "under --time-budget, fewer indirect rays per vertex for the per-pixel "
                  "display (down to 4 x 4) when its share of the budget would be overrun");
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

CLI::App* addSkyCommand(CLI::App& app, cli::SkyArgs& ka) {
    auto* sky = app.add_subcommand(
        "sky",
        "fit the scene's sky (environment light) to its photo and print it as an edit's "
        "sh9 (Wen et al. 2003)");
    sky->add_option("scene_dir", ka.scene, "scene folder holding scene.json")->required();
    sky->add_option("--photo", ka.photo,
                    "fit to this photo instead of the first (same camera and lights_on)");
    sky->add_option("--spp", ka.spp, "camera samples per pixel")->check(CLI::Range(1, 1024));
    return sky;
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
        ->add_option(
            "--display", ra.display,
            "ratio: T B/D everywhere (Loscos et al. 2000); confidence: the light an "
            "edit adds (lamps off in the photo, virtual parts) as the model's "
            "rho B / pi where the photo's lamps did not light a point (Loscos et al. "
            "1999's confidence); pixel: T H/H_photo with the direct light per pixel "
            "(Loscos et al. 1999; prepares with --pixel-light); ratio-map: L_o I_r / I_o "
            "with I the lights' direct irradiance per pixel (the 000 paper's Eq. 3); wen: as "
            "pixel, with the sky's part its unoccluded irradiance E(n) at the pixel's "
            "normal (Wen et al. 2003)")
        ->capture_default_str()
        ->check(CLI::IsMember({"ratio", "confidence", "pixel", "ratio-map", "wen"}));
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

/// `import colmap`: the options of relight/io/colmap_import.h, with the paths as strings
/// (CLI11 reads them so) and the optional values that have no "unset" value of their own.
struct ImportArgs {
    ColmapImportOptions o;
    std::string sparse, images, mesh, lights, objects, output;
    std::vector<std::string> lightsOn;
    double averageReflectance = -1;

    ColmapImportOptions options() const {
        ColmapImportOptions r = o;
        r.sparseDir = sparse;
        r.imagesDir = images;
        r.mesh = mesh;
        r.lights = lights;
        r.objects = objects;
        r.output = output;
        if (!lightsOn.empty()) r.lightsOn = lightsOn;
        if (averageReflectance >= 0) r.averageReflectance = averageReflectance;
        return r;
    }
};

CLI::App* addImportCommand(CLI::App& app, ImportArgs& ia) {
    auto* import = app.add_subcommand("import", "make a scene package from another tool's model");
    import->require_subcommand(1);
    auto* colmap = import->add_subcommand(
        "colmap", "a scene from a COLMAP model: one image's camera and photo, a mesh, lights");
    colmap
        ->add_option("sparse_dir", ia.sparse,
                     "COLMAP model folder: cameras.txt and images.txt, or cameras.bin and "
                     "images.bin")
        ->required();
    colmap->add_option("--image", ia.o.image, "the image's NAME in the model")->required();
    colmap->add_option("--images", ia.images, "COLMAP's image folder (the photo is DIR/NAME)")
        ->required();
    colmap->add_option("--mesh", ia.mesh, "the room's mesh: OBJ, PLY, glTF")->required();
    colmap->add_option("--lights", ia.lights,
                       "the real lights: the scene format's \"lights\" array, or a JSON object "
                       "holding one (default: none)");
    colmap->add_option("--objects", ia.objects,
                       "per-object settings: the format's \"objects\", or a scene.json holding "
                       "them");
    colmap->add_option("--lights-on", ia.lightsOn, "the lights on in the photo (default: all)")
        ->delimiter(',');
    colmap
        ->add_option("--average-reflectance", ia.averageReflectance,
                     "the user's guess of the scene's mean reflectance")
        ->check(CLI::Range(0.0, 0.999));
    colmap
        ->add_option("--encoding", ia.o.encoding,
                     "the photo's encoding (default: from its file type)")
        ->check(CLI::IsMember({"linear", "srgb"}));
    colmap->add_flag("--link", ia.o.link, "link the photo and the mesh instead of copying them");
    colmap->add_flag("--force", ia.o.force, "write into a folder that is not empty");
    colmap->add_option("-o,--output", ia.output, "the scene folder to write")->required();
    return colmap;
}

CLI::App* addExportCommand(CLI::App& app, cli::ExportColmapArgs& ea) {
    auto* exportApp = app.add_subcommand("export", "write a scene's camera for another tool");
    exportApp->require_subcommand(1);
    auto* colmap = exportApp->add_subcommand(
        "colmap", "the scene's camera as a COLMAP model (one PINHOLE camera, one image)");
    colmap->add_option("scene_dir", ea.scene, "scene folder holding scene.json")->required();
    colmap->add_option("-o,--output", ea.output, "the model folder to write")->required();
    colmap->add_flag("--binary", ea.binary, "cameras.bin and images.bin (default: text)");
    colmap->add_option("--name", ea.name, "the image's NAME (default: the photo's file name)");
    return colmap;
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
                     "error: unknown command \"%s\" (solve, prepare, render, eval, import or "
                     "export); "
                     "see "
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
    cli::SkyArgs ka;
    const CLI::App* sky = addSkyCommand(app, ka);
    const CLI::App* render = addRenderCommand(app, ra);
    const CLI::App* prepare = addPrepareCommand(app, pa);
    ImportArgs ia;
    const CLI::App* importColmap = addImportCommand(app, ia);
    cli::ExportColmapArgs xa;
    const CLI::App* exportColmap = addExportCommand(app, xa);
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
        if (*sky) return cli::runSky(ka);
        if (*importColmap) return cli::runImportColmap(ia.options());
        if (*exportColmap) return cli::runExportColmap(xa);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return exitCode(e);
    }
    return 0;
}
