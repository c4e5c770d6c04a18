// Moving a virtual box over the room's floor, frame by frame, and inserting a virtual
// light (Loscos et al. 2000, §5.1-5.2; Drettakis & Sillion 1997).
//
//   ./build/bench/move_box data [--epsilon E]     (default E = 5e-5: >= 5k leaves)
//
// Prepares data/room, inserts the box of edits/virtual_box.json at the photo's lighting,
// then moves it in `kSteps` equal steps to its place in edits/virtual_box_moved.json
// (translation and rotation interpolated). Each frame is a full update: the solver's move
// (removal, shafts of the link tree, visibility of the cut links, the box's links,
// gather/push-pull), the vertices whose direct light changed, the indirect change, and the
// display (ratio display of the whole image + the item buffer in the box's projected
// bounding box). Prints the median and 90th percentile of each part and of the frame.
// At the end of the path the frame is scored against the path-traced truth of
// virtual_box_moved, and compared with the same edit rendered from a fresh insertion.
// Then the light of edits/virtual_light_only.json is inserted and removed 5 times at the
// photo's lighting: the median insertion time (solver, vertices, display) at the photo's
// size.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/stopwatch.h"
#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

using namespace relight;
using bench::quantile;
using radiosity::Clock;
using radiosity::secondsSince;

namespace {

constexpr int kSteps = 40;

/// The box's polygons placed by a rotation about z by `angle` and a translation (x, y).
std::vector<radiosity::Polygon> placeBox(const std::vector<radiosity::Polygon>& local,
                                         const Rgb& rho, double angle, double x, double y) {
    std::vector<radiosity::Polygon> out;
    const double c = std::cos(angle), s = std::sin(angle);
    for (const auto& p : local) {
        std::vector<radiosity::Vec3> corners;
        for (int i = 0; i < p.vertexCount; ++i) {
            const auto& v = p.v[i];
            corners.push_back({c * v.x - s * v.y + x, s * v.x + c * v.y + y, v.z});
        }
        out.push_back(radiosity::makePolygon(corners, -1, rho));
    }
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    std::string data;
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.epsilon = 5e-5;
    o.pixelLight = true;  // for the per-pixel display's frames below
    if (!bench::parseDataAndEpsilon(argc, argv, data, o.epsilon)) return 2;
    try {
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        const std::string dir = data + "/room";
        auto r = prepareRelighting(loadScene(dir), o);
        const SceneFile& sf = r->scene;
        const auto photo = editRadiance(sf, EditFile{}, r->prepared.photoRadiance);
        const EditFile e0 = loadEdit(dir + "/edits/virtual_box.json", sf);
        const EditFile e1 = loadEdit(dir + "/edits/virtual_box_moved.json", sf);
        const EditFile eLight = loadEdit(dir + "/edits/virtual_light_only.json", sf);
        const VirtualObject& box = e0.addObjects.at(0);
        // The box in its own frame: the inverse of virtual_box's translation (no rotation).
        const double x0 = box.transform[0][3], y0 = box.transform[1][3];
        const auto& t1 = e1.addObjects.at(0).transform;
        const double x1 = t1[0][3], y1 = t1[1][3], angle1 = std::atan2(t1[1][0], t1[0][0]);
        const std::vector<radiosity::Polygon> local =
            placeBox(box.polygons, box.reflectance, 0, -x0, -y0);
        std::printf("room at epsilon %g: %d leaves, %d links, %zu leaf vertices, %dx%d\n",
                    o.epsilon, r->prepared.leaves, r->prepared.links, r->prepared.vertexCount(),
                    r->prepared.photo.width, r->prepared.photo.height);

        Image last;
        {
            DynamicRelighting dyn(*r, photo);
            dyn.addObject(box);
            dyn.render();
            std::vector<double> shafts, vis, links, radiosity, vertices, display, frame;
            std::vector<int> cut, tests;
            for (int i = 1; i <= kSteps; ++i) {
                const double t = static_cast<double>(i) / kSteps;
                const auto t0 = Clock::now();
                dyn.moveLastObject(placeBox(local, box.reflectance, t * angle1, x0 + t * (x1 - x0),
                                            y0 + t * (y1 - y0)));
                last = dyn.render();
                frame.push_back(secondsSince(t0));
                const FrameTimes& ft = dyn.times();
                shafts.push_back(ft.shafts);
                vis.push_back(ft.visibility);
                links.push_back(ft.links);
                radiosity.push_back(ft.radiosity);
                vertices.push_back(ft.vertices);
                display.push_back(ft.display);
                cut.push_back(dyn.lastUpdate().linksCut);
                tests.push_back(dyn.lastUpdate().shaftTests);
            }
            std::vector<double> cutD(cut.begin(), cut.end()), testsD(tests.begin(), tests.end());
            std::printf(
                "move the box, %d frames (%.2f m in all), seconds: median (90th percentile)\n",
                kSteps, std::hypot(x1 - x0, y1 - y0));
            const auto row = [](const char* name, const std::vector<double>& v) {
                std::printf("  %-34s %.4f (%.4f)\n", name, quantile(v, 0.5), quantile(v, 0.9));
            };
            row("shaft tests (link tree)", shafts);
            row("visibility rays of cut links", vis);
            row("removal + box links", links);
            row("radiosity (gather/push-pull)", radiosity);
            row("vertices (direct + indirect)", vertices);
            row("display (ratio + item buffer box)", display);
            row("frame", frame);
            std::printf("  frames per second (median): %.1f\n", 1.0 / quantile(frame, 0.5));
            std::printf("  shafts tested per frame %.0f, links cut %.0f (of %zu active)\n",
                        quantile(testsD, 0.5), quantile(cutD, 0.5), r->solver->links().size());
        }
        // The same path in the per-pixel display (relight render's default): the direct light
        // measured again at the pixels of the leaves the box's shafts cut, at each frame.
        {
            DynamicRelighting dyn(*r, photo);
            dyn.addObject(box);
            dyn.render(DisplayMode::pixel);
            std::vector<double> frame;
            Image end;
            for (int i = 1; i <= kSteps; ++i) {
                const double t = static_cast<double>(i) / kSteps;
                const auto t0 = Clock::now();
                dyn.moveLastObject(placeBox(local, box.reflectance, t * angle1, x0 + t * (x1 - x0),
                                            y0 + t * (y1 - y0)));
                end = dyn.render(DisplayMode::pixel);
                frame.push_back(secondsSince(t0));
            }
            int w = end.width, h = end.height;
            const Score s =
                scoreImage(end, readImage(dir + "/truth/virtual_box_moved.exr"), r->prepared.photo,
                           readMask(dir + "/truth/virtual_box_moved.mask.png", w, h),
                           readMask(dir + "/photo.mask.png", w, h));
            std::printf(
                "per-pixel display, the same path: frame %.4f s median (%.4f), %.1f frames per "
                "second; after it rel_rmse %.4f, changed_rel_rmse %.4f\n",
                quantile(frame, 0.5), quantile(frame, 0.9), 1.0 / quantile(frame, 0.5), s.relRmse,
                s.changedRelRmse);
        }
        // The end of the path is virtual_box_moved: against the truth and a fresh insertion.
        int w = last.width, h = last.height;
        const Score moved =
            scoreImage(last, readImage(dir + "/truth/virtual_box_moved.exr"), r->prepared.photo,
                       readMask(dir + "/truth/virtual_box_moved.mask.png", w, h),
                       readMask(dir + "/photo.mask.png", w, h));
        Image fresh;
        {
            DynamicRelighting dyn(*r, photo);
            dyn.addObject(e1.addObjects.at(0));
            fresh = dyn.render();
        }
        std::printf(
            "after the path: rel_rmse %.4f, changed_rel_rmse %.4f against the truth of "
            "virtual_box_moved; %.5f rel. RMS from a fresh insertion there\n",
            moved.relRmse, moved.changedRelRmse, relativeRmsDifference(last, fresh));

        {
            DynamicRelighting dyn(*r, photo);
            std::vector<double> insert;
            for (int i = 0; i < 6; ++i) {
                const auto t0 = Clock::now();
                dyn.addLight(eLight.addLights.at(0));
                dyn.render();
                insert.push_back(secondsSince(t0));
                const FrameTimes& ft = dyn.times();
                if (i == 5)
                    std::printf(
                        "  last insertion: shafts %.4f, visibility %.4f, links %.4f, "
                        "radiosity %.4f, vertices %.4f, display %.4f s; %d new links\n",
                        ft.shafts, ft.visibility, ft.links, ft.radiosity, ft.vertices, ft.display,
                        dyn.lastUpdate().linksNew);
                dyn.removeLast();
            }
            std::printf(
                "insert a virtual light at %dx%d: first %.4f s (with the final gather of "
                "the edit's indirect light before it), then median %.4f s (%.4f)\n",
                r->prepared.photo.width, r->prepared.photo.height, insert[0],
                quantile({insert.begin() + 1, insert.end()}, 0.5),
                quantile({insert.begin() + 1, insert.end()}, 0.9));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
