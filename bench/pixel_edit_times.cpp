// Time of a light edit in the per-pixel display (issue 32: <= 1 ms at 320x240, <= 10 ms at
// 1280x960 on the CPU; issue 31: the sky turned <= 5 ms at 320x240), the fast path
// (renderEdit, relight/pipeline/pixel_light_table.h) against the general path it replaced
// (renderPixelEditReference), in the same run, on 2 threads.
//
//   ./build/bench/pixel_edit_times SCENE_DIR [--edits N]
//
// Prepares the scene with per-pixel light (RelightOptions::pixelLight, relight render's
// default), then renders N edits by each path into an image reused from edit to edit:
//   - "scalings": every light scaled by a random factor in [0, 2] (all lights change);
//   - "slider": one light's scale moved in steps, the others as in the photo;
//   - "sky turned" (scenes with a light named "sky"): editRadiance() of a turn about z by a
//     different angle each time, then the render, as daylight_edit_times.
// Prints the median and 90th percentile wall time per edit and the process's CPU time
// (user + system, getrusage) per edit, for each path, and the ratio of the medians.
#include <sys/resource.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/stopwatch.h"
#include "relight/io/edit_file.h"
#include "relight/relighting.h"

using namespace relight;
using radiosity::Clock;
using radiosity::Rgb;
using radiosity::secondsSince;

namespace {

double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

struct Timing {
    double median = 0, p90 = 0, cpu = 0;  ///< seconds per edit
};

/// Runs frame(i) for i in [0, n): wall times and CPU time per frame.
Timing timeFrames(int n, const std::function<void(int)>& frame) {
    frame(0);  // the image's first allocation and the caches' first touch are not an edit's
    std::vector<double> t;
    const double c0 = cpuSeconds();
    for (int i = 0; i < n; ++i) {
        const auto t0 = Clock::now();
        frame(i);
        t.push_back(secondsSince(t0));
    }
    return {bench::quantile(t, 0.5), bench::quantile(t, 0.9), (cpuSeconds() - c0) / n};
}

void report(const char* what, const Timing& ref, const Timing& fast) {
    std::printf(
        "%-12s reference: median %7.3f ms, p90 %7.3f ms, CPU %7.3f ms | fast: median %7.3f "
        "ms, p90 %7.3f ms, CPU %7.3f ms | %.1fx\n",
        what, ref.median * 1e3, ref.p90 * 1e3, ref.cpu * 1e3, fast.median * 1e3, fast.p90 * 1e3,
        fast.cpu * 1e3, fast.median > 0 ? ref.median / fast.median : 0.0);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s SCENE_DIR [--edits N]\n", argv[0]);
        return 2;
    }
    const std::string dir = argv[1];
    int n = 48;
    for (int i = 2; i + 1 < argc; ++i)
        if (!std::strcmp(argv[i], "--edits")) n = std::max(1, std::atoi(argv[++i]));
    std::setvbuf(stdout, nullptr, _IOLBF, 0);
    std::printf("command: %s %s --edits %d\n", argv[0], dir.c_str(), n);
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.pixelLight = true;
    const auto r = prepareRelighting(loadScene(dir), o);
    const PreparedImage& P = r->prepared;
    std::printf("%dx%d photo, %zu lights, %zu vertices, %zu pixels drawn by the ratio display\n",
                P.photo.width, P.photo.height, P.photoRadiance.size(), P.vertexCount(),
                P.pixelTable.ratioPixels.size());
    if (P.pixelTable.empty()) std::printf("(no fast table: both paths are the reference)\n");

    std::mt19937 rng(1);
    std::uniform_real_distribution<double> scale(0.0, 2.0);
    std::vector<std::vector<Rgb>> scalings(static_cast<size_t>(n), P.photoRadiance);
    for (auto& L : scalings)
        for (auto& l : L) l = l * scale(rng);
    std::vector<std::vector<Rgb>> slider(static_cast<size_t>(n), P.photoRadiance);
    for (int i = 0; i < n; ++i) slider[static_cast<size_t>(i)][0] = P.photoRadiance[0] * (0.05 * i);

    Image out;
    auto byRef = [&](const std::vector<std::vector<Rgb>>& e) {
        return timeFrames(
            n, [&](int i) { renderPixelEditReference(P, e[static_cast<size_t>(i)], out); });
    };
    auto byFast = [&](const std::vector<std::vector<Rgb>>& e) {
        return timeFrames(
            n, [&](int i) { renderEdit(P, e[static_cast<size_t>(i)], out, DisplayMode::pixel); });
    };
    const Timing refScalings = byRef(scalings), fastScalings = byFast(scalings);
    report("scalings", refScalings, fastScalings);
    const Timing refSlider = byRef(slider), fastSlider = byFast(slider);
    report("slider", refSlider, fastSlider);

    std::vector<EditFile> turns;
    try {
        for (int i = 0; i < n; ++i) {
            std::istringstream in(
                R"({"format": "relight-edit/1", "lights": {"sky": {"rotate": {"axis": [0, 0, 1], "degrees": )" +
                std::to_string(120 + i) + "}}}}");
            turns.push_back(parseEdit(in, r->scene.dir / "bench_edit.json", r->scene));
        }
    } catch (const std::exception&) {
        return 0;  // no light named "sky"
    }
    auto turned = [&](bool fast) {
        return timeFrames(n, [&](int i) {
            const auto L = editRadiance(r->scene, turns[static_cast<size_t>(i)], P.photoRadiance);
            if (fast)
                renderEdit(P, L, out, DisplayMode::pixel);
            else
                renderPixelEditReference(P, L, out);
        });
    };
    const Timing refSky = turned(false), fastSky = turned(true);
    report("sky turned", refSky, fastSky);
    return 0;
}
