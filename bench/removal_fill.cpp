// Real-object removal against the path tracer (issue 34): each `remove_*` edit of a scene
// with its truth, the hidden surfaces synthesised in their rectified planes by
// non-parametric sampling (the default) and by OpenCV's cv::inpaint (the baseline), relit
// in the per-pixel display (relight render's default) and scored with the spec's metric
// (rel_rmse / changed_rel_rmse, as `relight eval`), with the time of the removal (the
// solver's update, the fill, the direct light at the revealed samples) and of the first
// frame. The scene is prepared once with render's default settings.
//
//   ./build/bench/removal_fill [SCENE_DIR] [--write DIR]     (default: data/room)
//
// --write DIR: each image as DIR/<edit>-<method>.png (sRGB, as relight render writes) and
// .exr (linear, for bench/removal_strip.py).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "radiosity/stopwatch.h"
#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

using namespace relight;
using radiosity::Clock;
using radiosity::secondsSince;
namespace fs = std::filesystem;

namespace {

Score score(const fs::path& dir, const std::string& edit, const Image& image, const Image& photo) {
    int w = image.width, h = image.height;
    return scoreImage(image, readImage(dir / "truth" / (edit + ".exr")), photo,
                      readMask(dir / "truth" / (edit + ".mask.png"), w, h),
                      readMask(dir / "photo.mask.png", w, h));
}

}  // namespace

int main(int argc, char** argv) {
    fs::path dir = "data/room", write;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--write" && i + 1 < argc)
            write = argv[++i];
        else
            dir = a;
    }
    std::printf("command: ./build/bench/removal_fill %s%s\n", dir.c_str(),
                write.empty() ? "" : (" --write " + write.string()).c_str());
    RelightOptions options;
    options.pixelLight = true;  // relight render's default display
    auto r = prepareRelighting(loadScene(dir), options);
    std::printf("%s: %dx%d, prepared with the default settings\n", dir.c_str(), r->items.width,
                r->items.height);
    std::printf("%-16s %-9s %17s %8s %8s %9s %9s\n", "edit", "fill", "rel_rmse / changed",
                "removal", "fill", "1st frame", "pixels");
    for (const auto& entry : fs::directory_iterator(dir / "edits")) {
        const std::string edit = entry.path().stem().string();
        if (edit.rfind("remove_", 0) != 0 || !fs::exists(dir / "truth" / (edit + ".exr"))) continue;
        const EditFile e = loadEdit(entry.path(), r->scene);
        const Score photo = score(dir, edit, r->prepared.photo, r->prepared.photo);
        std::printf("%-16s %-9s %8.4f / %6.4f\n", edit.c_str(), "(photo)", photo.relRmse,
                    photo.changedRelRmse);
        for (const auto method : {SurfaceSynthesis::exemplar, SurfaceSynthesis::inpaint}) {
            const char* name = method == SurfaceSynthesis::exemplar ? "exemplar" : "inpaint";
            DynamicRelighting dyn(*r, editRadiance(r->scene, e, r->prepared.photoRadiance));
            dyn.setSurfaceSynthesis(method);
            const auto t0 = Clock::now();
            for (const auto& object : e.removeObjects) dyn.removeObject(object);
            const double removal = secondsSince(t0);
            const auto t1 = Clock::now();
            const Image image = dyn.render(DisplayMode::pixel);
            const double frame = secondsSince(t1);
            const Score s = score(dir, edit, image, r->prepared.photo);
            const RemovedRegion& g = dyn.removedRegion();
            std::printf("%-16s %-9s %8.4f / %6.4f %7.2fs %7.2fs %8.2fs %9d\n", edit.c_str(), name,
                        s.relRmse, s.changedRelRmse, removal, dyn.times().fill, frame,
                        g.filled + g.modelled);
            if (!write.empty()) {
                fs::create_directories(write);
                writeImage(write / (edit + "-" + name + ".png"), image);
                writeImage(write / (edit + "-" + name + ".exr"), image);
            }
            std::fflush(stdout);
        }
    }
    return 0;
}
