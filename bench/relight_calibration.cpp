// Relighting under calibration error: what each step of the method buys when the model's
// lamps are not where the photo's lamps were.
//
//   ./build/bench/relight_calibration data [--epsilon E]
//
// The photo and the path-traced truth of data/room are kept; the model's lamps are moved
// by delta = 0, 2, 5 and 10 cm in their own plane, each in another direction (lamp l along
// cos(t) e1 + sin(t) e2 with t = pi/4 + l pi/2, e1 and e2 its first two edges' unit
// vectors), so the shadows the model computes no longer fall exactly where the photo shows
// them. For each delta, the room is prepared three ways (1997: BF refinement only, no
// shadow removal; +refine: texture-based refinement of shadow boundaries, §4.2; full:
// refinement and real-shadow removal, §4.3-4.5) and every light edit is scored against
// its truth (spec metric). It prints rel_rmse per edit, and the mean over the four edits
// that change the lights.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/stopwatch.h"
#include "relight/display/metric.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

using namespace relight;

namespace {

/// The scene with every lamp's emitting faces moved by `delta` metres (see above).
SceneFile withLampsMoved(SceneFile sf, double delta) {
    radiosity::Scene& scene = sf.scene;
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const auto& first = scene.polygons[scene.lights[l].polygons.front()];
        const radiosity::Vec3 e1 = glm::normalize(first.v[1] - first.v[0]);
        const radiosity::Vec3 e2 = glm::normalize(first.v[first.vertexCount - 1] - first.v[0]);
        const double t = std::numbers::pi / 4 + static_cast<double>(l) * std::numbers::pi / 2;
        const radiosity::Vec3 shift = delta * (std::cos(t) * e1 + std::sin(t) * e2);
        for (int p : scene.lights[l].polygons)
            for (int i = 0; i < scene.polygons[p].vertexCount; ++i) scene.polygons[p].v[i] += shift;
    }
    return sf;
}

}  // namespace

int main(int argc, char** argv) {
    std::string data;
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    if (!bench::parseDataAndEpsilon(argc, argv, data, o.epsilon)) return 2;
    try {
        const std::string dir = data + "/room";
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        const SceneFile calibrated = loadScene(dir);
        const std::vector<std::string> edits = {"identity", "back_off", "left_off_right_double",
                                                "right_off_left_double", "colours"};
        int w = 0, h = 0;
        const auto maskP = readMask(dir + "/photo.mask.png", w, h);
        std::vector<Image> truth;
        std::vector<std::vector<uint8_t>> maskT;
        std::vector<EditFile> edit;
        for (const auto& name : edits) {
            truth.push_back(readImage(dir + "/truth/" + name + ".exr"));
            maskT.push_back(readMask(dir + "/truth/" + name + ".mask.png", w, h));
            edit.push_back(loadEdit(dir + "/edits/" + name + ".json", calibrated));
        }

        struct Variant {
            const char* name;
            bool refinement, removal;
        };
        const Variant variants[] = {
            {"1997", false, false}, {"+refine", true, false}, {"full", true, true}};
        std::printf("\n== rel_rmse against truth/<edit>.exr with the model's lamps moved\n");
        std::printf("   %-6s %-8s", "delta", "variant");
        for (const auto& name : edits) std::printf(" %12.12s", name.c_str());
        std::printf(" %10s %9s\n", "mean edit", "prepare");
        for (double delta : {0.0, 0.02, 0.05, 0.10}) {
            const SceneFile moved = withLampsMoved(calibrated, delta);
            for (const Variant& v : variants) {
                RelightOptions ov = o;
                ov.shadowRefinement = v.refinement;
                ov.shadowRemoval = v.removal;
                const auto t0 = radiosity::Clock::now();
                const auto r = prepareRelighting(moved, ov);
                const double tPrepare = radiosity::secondsSince(t0);
                std::printf("   %4.0fcm %-8s", delta * 100, v.name);
                double sum = 0;
                for (size_t e = 0; e < edits.size(); ++e) {
                    const Image img = renderEdit(
                        r->prepared, editRadiance(r->scene, edit[e], r->prepared.photoRadiance));
                    const Score sc = scoreImage(img, truth[e], r->prepared.photo, maskT[e], maskP);
                    std::printf(" %12.4f", sc.relRmse);
                    if (e > 0) sum += sc.relRmse;
                }
                std::printf(" %10.4f %8.2fs\n", sum / static_cast<double>(edits.size() - 1),
                            tPrepare);
                std::fflush(stdout);
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
