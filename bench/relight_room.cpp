// Relighting the room's photo: accuracy of each light edit against the path-traced truth,
// and the time of each pipeline step and of an edit.
//
//   ./build/bench/relight_room data [--epsilon E]
//
// For each light edit of data/room (identity, back_off, left_off_right_double,
// right_off_left_double, colours) it prints rel_rmse (and changed_rel_rmse, spec metric)
// of:
//   photo      the photo unchanged (the baseline that does nothing);
//   1997       T * B/D at the leaf vertices, BF refinement only, no shadow removal (the
//              method of Drettakis et al. 1997: Loscos et al. 2000, Fig. 9(c));
//   +refine    the same after texture-based refinement of shadow boundaries (§4.2);
//   full       refinement and real-shadow removal (§4.3-4.5), the engine's default;
// then the times of the preparation steps, the median time of a light edit by
// superposition (vertex weighted sums + display at the photo's size), and of the same
// edit by gather/push-pull on the solver's links followed by the final gather at the
// vertices.
#include <tbb/global_control.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/final_gather.h"
#include "radiosity/stopwatch.h"
#include "relight/display/metric.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/pipeline/vertex_lighting.h"
#include "relight/relighting.h"

using namespace relight;
using radiosity::Clock;
using radiosity::secondsSince;

int main(int argc, char** argv) {
    std::string data;
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    if (!bench::parseDataAndEpsilon(argc, argv, data, o.epsilon)) return 2;
    try {
        const std::string dir = data + "/room";
        tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
        // The three variants, each prepared from scratch; the last (the default) is timed
        // and used for the edit timings below.
        RelightOptions o1997 = o, oRefine = o;
        o1997.shadowRefinement = false;
        o1997.shadowRemoval = false;
        oRefine.shadowRemoval = false;
        const auto r1997 = prepareRelighting(loadScene(dir), o1997);
        const auto rRefine = prepareRelighting(loadScene(dir), oRefine);
        auto t0 = Clock::now();
        const auto r = prepareRelighting(loadScene(dir), o);
        const double tPrepare = secondsSince(t0);
        const auto st = r->solver->stats();
        std::printf(
            "\n== prepare (2 threads): %.3f s; %d leaves (%d before shadow refinement), "
            "%d links, %zu leaf vertices\n",
            tPrepare, st.leaves, r->refinement.leavesBefore, st.links, r->mesh->vertices().size());
        std::printf("   %s s\n", stepTimes(r->prepared.times).c_str());
        std::printf("   refinement: %d splits kept (%d same colour, %d other colour), %d undone\n",
                    r->refinement.splitSameColour + r->refinement.splitDifferentColour,
                    r->refinement.splitSameColour, r->refinement.splitDifferentColour,
                    r->refinement.undone);
        std::printf(
            "   removal: %d occluded leaves, %d frontier, %d with a reference; %d vertices "
            "with C_link, %d with C_umbra\n",
            r->removal.occluded, r->removal.frontier, r->removal.referenced,
            r->removal.partialVertices, r->removal.umbraVertices);

        int w = 0, h = 0;
        const auto maskP = readMask(dir + "/photo.mask.png", w, h);
        const char* edits[] = {"identity", "back_off", "left_off_right_double",
                               "right_off_left_double", "colours"};
        std::printf(
            "\n== accuracy against truth/<edit>.exr (spec metric: rel_rmse, and "
            "changed_rel_rmse in brackets)\n");
        std::printf("   %-24s %18s %18s %18s %18s\n", "edit", "photo", "1997", "+refine", "full");
        double worstEditTime = 0;
        std::vector<double> superpose;
        const Image& photo = r->prepared.photo;
        for (const char* name : edits) {
            const EditFile e = loadEdit(dir + "/edits/" + name + ".json", r->scene);
            const auto radiance = editRadiance(r->scene, e, r->prepared.photoRadiance);
            const Image truth = readImage(dir + "/truth/" + name + ".exr");
            const auto maskT = readMask(dir + "/truth/" + name + ".mask.png", w, h);
            std::printf("   %-24s", name);
            auto show = [&](const Image& img) {
                const Score sc = scoreImage(img, truth, photo, maskT, maskP);
                std::printf(" %8.4f (%7.4f)", sc.relRmse, sc.hasChanged ? sc.changedRelRmse : 0.0);
            };
            show(photo);
            show(renderEdit(r1997->prepared, radiance));
            show(renderEdit(rRefine->prepared, radiance));
            show(renderEdit(r->prepared, radiance));
            std::printf("\n");
            // Timing of the superposition path, one thread (the median of 50 runs).
            {
                tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
                std::vector<double> t;
                for (int i = 0; i < 50; ++i) {
                    const auto t1 = Clock::now();
                    const Image img = renderEdit(r->prepared, radiance);
                    t.push_back(secondsSince(t1));
                }
                std::nth_element(t.begin(), t.begin() + 25, t.end());
                superpose.push_back(t[25]);
                worstEditTime = std::max(worstEditTime, t[25]);
            }
        }
        // The gather/push-pull path for one edit (on the variant without shadow removal,
        // whose vertex direct light is the plain per-point one the final gather computes):
        // re-gather the solver's links with the new radiances, then the final gather at every
        // vertex (2 threads).
        {
            const EditFile e = loadEdit(dir + "/edits/left_off_right_double.json", rRefine->scene);
            const auto radiance = editRadiance(rRefine->scene, e, rRefine->prepared.photoRadiance);
            t0 = Clock::now();
            rRefine->solver->setLightRadiances(radiance);
            const double tGather = secondsSince(t0);
            // Vertex irradiance from the re-gathered solution: direct light per vertex and
            // the final gather of its links (the same as the prepared responses, summed).
            t0 = Clock::now();
            const int nv = static_cast<int>(rRefine->mesh->vertices().size());
            std::vector<radiosity::Rgb> H(static_cast<size_t>(nv));
            const radiosity::DirectLight direct(*rRefine->solver);
            for (int v = 0; v < nv; ++v) {
                const int p = rRefine->mesh->vertices()[v].polygon;
                if (rRefine->solver->scene().polygons[p].light >= 0) continue;
                H[v] = radiosity::gatheredIrradiance(*rRefine->solver, direct, p,
                                                     rRefine->mesh->insidePoint(v),
                                                     static_cast<uint64_t>(v));
            }
            const double tVertex = secondsSince(t0);
            // The two paths agree to the solution's convergence tolerance.
            const auto Hsum = vertexIrradiance(rRefine->prepared, radiance);
            double maxH = 0, maxDiff = 0;
            for (int v = 0; v < nv; ++v) {
                maxH = std::max(maxH, Hsum[v].maxComponent());
                for (int c = 0; c < 3; ++c)
                    maxDiff = std::max(maxDiff, std::abs(H[v][c] - Hsum[v][c]));
            }
            std::printf(
                "\n   gather path vs superposition at the vertices: max difference %.2e of max H\n",
                maxH > 0 ? maxDiff / maxH : 0.0);
            rRefine->solver->setLightRadiances(rRefine->prepared.photoRadiance);
            std::printf(
                "\n== light edit at %dx%d\n   superposition (1 thread): median %.3f ms (worst "
                "edit's median)\n   gather/push-pull on the links: %.3f s, then the vertex "
                "irradiance by final gather %.3f s (1 thread)\n",
                r->prepared.photo.width, r->prepared.photo.height, worstEditTime * 1e3, tGather,
                tVertex);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
