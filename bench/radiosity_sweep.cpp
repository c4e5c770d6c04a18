// radiosity_sweep: run time against error of the hierarchical solver.
//
//   radiosity_sweep <data_dir> [--quick]
//
// For the Cornell box and the room (scene.json reflectances, lights of the first photo):
//  1. a full-matrix reference solution on a uniform mesh;
//  2. for each epsilon and rays-per-link setting, one hierarchical solve on ONE core:
//     elements, links, rays, solve time, and the relative RMS error against the reference
//     (area-weighted over the reference's elements, all channels);
//  3. gather + push-pull throughput: link updates per second on one core;
//  4. Cornell against the path-traced truth: the `relight solve -o` pipeline (reflectance
//     from the photo, 16 samples per pixel) scored by the spec's metric against
//     truth/identity.exr; the time is that of a fresh solve with the estimated
//     reflectances, on one core.
// Writes bench/figures/time_vs_error.png (log-log plot) when OpenImageIO can draw it.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "plot.h"
#include "radiosity/final_gather.h"
#include "radiosity/leaf_mesh.h"
#include "radiosity/reference_solver.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/display/metric.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/reflectance.h"

using namespace radiosity;
using radiosity::Clock;
using radiosity::secondsSince;

namespace {

struct Row {
    double eps;
    int minRays, maxRays;
    SolverStats st;
    double seconds, error;
    double errorVertex;                     ///< leaf B averaged at vertices, interpolated
    double errorGathered, secondsGathered;  ///< final gather at 16 points per element
};

std::vector<Row> sweepScene(const std::string& name, const Scene& scene, double refArea,
                            const std::vector<double>& epsilons,
                            const std::vector<std::pair<int, int>>& rays) {
    std::printf("\n== %s: reference (uniform mesh, elements <= %.4g m^2, 16 rays per pair)\n",
                name.c_str(), refArea);
    auto t0 = Clock::now();
    ReferenceOptions ro;
    ro.maxArea = refArea;
    ReferenceSolver ref(scene, ro);
    {
        tbb::global_control all(tbb::global_control::max_allowed_parallelism, 2);
        ref.solve();
    }
    std::printf("   %zu elements, %d Gauss-Seidel sweeps, %.1f s (2 threads)\n",
                ref.leaves().size(), ref.sweeps(), secondsSince(t0));
    std::printf("   %-8s %-6s %8s %8s %9s %10s %9s %8s %8s %8s %9s\n", "epsilon", "rays", "leaves",
                "links", "passive", "rays cast", "solve s", "rel err", "vertex", "gathered",
                "gather s");
    std::vector<Row> rows;
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    for (auto [minR, maxR] : rays) {
        for (double eps : epsilons) {
            SolverOptions o;
            o.epsilon = eps;
            o.transfer.minRays = minR;
            o.transfer.maxRays = maxR;
            t0 = Clock::now();
            HierarchicalSolver hr(scene, o);
            hr.solve();
            const double secs = secondsSince(t0);
            const double err =
                relativeRmsError(ref, [&](int p, const Vec3& x) { return hr.radiosityAt(p, x); });
            // The same solution read by final gather at each point (per-point direct
            // light, indirect through the links), as the renderer shows it.
            t0 = Clock::now();
            const DirectLight direct(hr);
            uint64_t seed = 0;
            const double errGather = relativeRmsError(ref, [&](int p, const Vec3& x) {
                return gatheredRadiosity(hr, direct, p, x, ++seed);
            });
            const double secsGather = secondsSince(t0);
            // The paper's display: leaf values averaged at the leaf vertices (Gouraud) and
            // interpolated across each leaf.
            const LeafMesh mesh(hr.hierarchy());
            const auto& nodes = hr.hierarchy().nodes;
            const auto vAvg = mesh.averageOfLeaves([&](int n) { return nodes[n].B; });
            const double errVertex = relativeRmsError(
                ref, [&](int p, const Vec3& x) { return mesh.interpolate(vAvg, p, x); });
            Row r{eps, minR, maxR, hr.stats(), secs, err, errVertex, errGather, secsGather};
            std::printf("   %-8.0e %2d/%-3d %8d %8d %9d %10llu %9.3f %8.4f %8.4f %8.4f %9.3f\n",
                        eps, minR, maxR, r.st.leaves, r.st.links, r.st.passiveLinks,
                        static_cast<unsigned long long>(r.st.rays), secs, err, errVertex, errGather,
                        secsGather);
            std::fflush(stdout);
            rows.push_back(r);
        }
    }
    return rows;
}

void throughput(const std::string& name, const Scene& scene, double eps) {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    SolverOptions o;
    o.epsilon = eps;
    HierarchicalSolver hr(scene, o);
    hr.solve();
    const int sweeps = 50;
    auto t0 = Clock::now();
    for (int i = 0; i < sweeps; ++i) hr.sweep();
    const double secs = secondsSince(t0);
    const double updates = static_cast<double>(hr.links().size()) * sweeps;
    std::printf(
        "\n== %s gather + push-pull, 1 core, epsilon %g: %zu links, %d nodes, %d sweeps in %.3f s: "
        "%.1f M link-updates/s\n",
        name.c_str(), eps, hr.links().size(), static_cast<int>(hr.hierarchy().nodes.size()), sweeps,
        secs, updates / secs * 1e-6);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <data_dir> [--quick]\n", argv[0]);
        return 2;
    }
    const std::string data = argv[1];
    const bool quick = argc > 2 && std::strcmp(argv[2], "--quick") == 0;
    std::printf("command: %s %s%s\n", argv[0], data.c_str(), quick ? " --quick" : "");
    try {
        const auto cornell = relight::loadScene(data + "/cornell");
        const auto room = relight::loadScene(data + "/room");
        std::vector<double> eps = {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5};
        if (!quick) eps.push_back(3e-6);
        const std::vector<std::pair<int, int>> rays =
            quick ? std::vector<std::pair<int, int>>{{4, 16}}
                  : std::vector<std::pair<int, int>>{{4, 16}, {8, 64}};
        auto rowsC = sweepScene("cornell", cornell.scene, quick ? 0.004 : 0.001, eps, rays);
        auto rowsR = sweepScene("room", room.scene, quick ? 0.1 : 0.04, eps, {{4, 16}});
        throughput("cornell", cornell.scene, 1e-5);
        throughput("room", room.scene, 1e-4);

        // Cornell against the path-traced truth.
        std::printf(
            "\n== cornell vs truth/identity.exr (reflectance from the photo, 16 spp, spec "
            "metric)\n");
        std::printf("   %-8s %8s %8s %10s %10s %12s %9s\n", "epsilon", "leaves", "links", "solve s",
                    "render s", "estimate s", "rel_rmse");
        relight::Image photo = relight::readImage(cornell.photos[0].file);
        relight::Image truth = relight::readImage(data + "/cornell/truth/identity.exr");
        int w, h;
        auto maskT = relight::readMask(data + "/cornell/truth/identity.mask.png", w, h);
        auto maskP = relight::readMask(data + "/cornell/photo.mask.png", w, h);
        std::vector<std::pair<double, double>> truthCurve;
        for (double e : eps) {
            tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
            SolverOptions o;
            o.epsilon = e;
            auto t0 = Clock::now();
            HierarchicalSolver est(cornell.scene, o);
            auto items = relight::castItemBuffer(cornell.camera, est.scene(), est.visibility(), 16);
            est.solve();
            auto estLighting = relight::computeLightingBuffer(items, est);
            relight::estimatePolygonReflectance(est, cornell, items, estLighting, photo);
            const double tEst = secondsSince(t0);
            t0 = Clock::now();
            HierarchicalSolver hr(est.scene(), o);  // a fresh solve with the estimated reflectances
            hr.solve();
            const double tSolve = secondsSince(t0);
            t0 = Clock::now();
            auto lighting = relight::computeLightingBuffer(items, hr);
            relight::updateIndirect(lighting, hr);
            relight::Image img = relight::renderRadiosity(items, lighting, hr.scene());
            const double tRender = secondsSince(t0);
            const auto score = relight::scoreImage(img, truth, photo, maskT, maskP);
            const auto st = hr.stats();
            std::printf("   %-8.0e %8d %8d %10.3f %10.3f %12.3f %9.4f\n", e, st.leaves, st.links,
                        tSolve, tRender, tEst, score.relRmse);
            std::fflush(stdout);
            truthCurve.push_back({tSolve, score.relRmse});
        }
        // Plot: solve time (x, log) against error (y, log).
        std::vector<bench::Series> series;
        auto toSeries = [](const std::vector<Row>& rows, int maxR, const char* label,
                           bench::Colour c) {
            bench::Series s{label, c, {}};
            for (const Row& r : rows)
                if (r.maxRays == maxR) s.points.push_back({r.seconds, r.error});
            return s;
        };
        series.push_back(toSeries(rowsC, 16, "cornell vs ref., 4/16 rays", {0.85f, 0.2f, 0.2f}));
        if (!quick)
            series.push_back(
                toSeries(rowsC, 64, "cornell vs ref., 8/64 rays", {0.95f, 0.6f, 0.2f}));
        series.push_back(toSeries(rowsR, 16, "room vs ref., 4/16 rays", {0.2f, 0.4f, 0.9f}));
        auto gathered = [](const std::vector<Row>& rows, const char* label, bench::Colour c) {
            bench::Series s{label, c, {}};
            for (const Row& r : rows)
                if (r.maxRays == 16) s.points.push_back({r.seconds, r.errorGathered});
            return s;
        };
        series.push_back(
            gathered(rowsC, "cornell vs ref., read by final gather", {0.6f, 0.1f, 0.5f}));
        series.push_back(gathered(rowsR, "room vs ref., read by final gather", {0.1f, 0.7f, 0.8f}));
        series.push_back({"cornell image vs truth", {0.1f, 0.7f, 0.3f}, truthCurve});
        const std::string png = "bench/figures/time_vs_error.png";
        if (bench::plotLogLog(png, series, "solve time, one core (s)", "relative RMS error"))
            std::printf("\nwrote %s\n", png.c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
