// The SH9 sky layer's costs (radiosity/sh9.h, radiosity/sky_transfer.h):
//   1. turning the sky and relighting every pixel: rotate the 9 RGB coefficients (the edit's
//      `rotate`), then each pixel's radiance (rho / pi) sum_k T_pk L'_k, a 9-term dot
//      product per channel, at 320x240 and 1280x960; median and 90th percentile of 30
//      frames, on one thread and on all of TBB's (the bound: <= 5 ms at 320x240);
//   2. the transfer vectors of N points with R rays each (Visibility's segment packets), on
//      the courtyard's geometry: N points spread over its faces by area, each on its face.
//
//   ./build/bench/sh9_bench /work/shared/data/courtyard [--points N] [--rays R1,R2,...]
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/detail/rng.h"
#include "radiosity/hierarchy.h"
#include "radiosity/parallel.h"
#include "radiosity/sh9.h"
#include "radiosity/sky_transfer.h"
#include "radiosity/stopwatch.h"
#include "relight/io/obj_reader.h"
#include "tests/support/skies.h"

using radiosity::Rgb;
using radiosity::Sh9;
using radiosity::Sh9Rgb;
using radiosity::Vec3;

namespace {

using radiosity::test::clearSky;  // tests/support/skies.h

// Median and 90th percentile (ms) of `frames` calls of f.
template <class F>
void timeFrames(const char* label, int frames, F&& f) {
    std::vector<double> ms;
    for (int i = 0; i < frames; ++i) {
        const auto t0 = radiosity::Clock::now();
        f(i);
        ms.push_back(1e3 * radiosity::secondsSince(t0));
    }
    std::printf("  %-22s median %8.3f ms   p90 %8.3f ms\n", label, bench::quantile(ms, 0.5),
                bench::quantile(ms, 0.9));
}

void benchTurn(int width, int height) {
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    std::mt19937 rng(1);
    std::normal_distribution<double> g;
    std::uniform_real_distribution<double> u(0.1, 0.9);
    std::vector<Sh9> T(n);
    std::vector<Rgb> rho(n), image(n);
    for (size_t p = 0; p < n; ++p) {
        T[p] = radiosity::sh9CosineTransfer(glm::normalize(Vec3{g(rng), g(rng), g(rng)}));
        rho[p] = {u(rng), u(rng), u(rng)};
    }
    const Sh9Rgb sky = clearSky();
    const double invPi = 1 / 3.14159265358979323846;
    auto pixel = [&](const Sh9Rgb& L, size_t p) {
        image[p] = rho[p] * radiosity::sh9Dot(T[p], L) * invPi;
    };
    std::printf("%dx%d (%zu pixels):\n", width, height, n);
    timeFrames("1 thread", 30, [&](int frame) {
        const Sh9Rgb L = radiosity::sh9RotateAboutAxis(sky, {0, 0, 1}, 3.0 * frame);
        for (size_t p = 0; p < n; ++p) pixel(L, p);
    });
    const std::string all = std::to_string(tbb::this_task_arena::max_concurrency()) + " threads";
    timeFrames(all.c_str(), 30, [&](int frame) {
        const Sh9Rgb L = radiosity::sh9RotateAboutAxis(sky, {0, 0, 1}, 3.0 * frame);
        radiosity::parallelForChunks(n, 4096, [&](size_t b, size_t e) {
            for (size_t p = b; p < e; ++p) pixel(L, p);
        });
    });
}

// The courtyard's faces as a radiosity scene (faces that are not planar convex polygons
// are skipped: the loader would repair them; here only the occluders matter).
radiosity::Scene loadGeometry(const std::string& obj) {
    const relight::ObjFile file = relight::readObj(obj);
    radiosity::Scene scene;
    scene.objects = file.objects;
    for (const relight::ObjFace& f : file.faces) {
        std::vector<Vec3> corners;
        for (const int v : f.vertices) corners.push_back(file.positions[static_cast<size_t>(v)]);
        if (corners.size() > 4 ||
            radiosity::checkPolygon(corners).status != radiosity::PolygonCheck::Status::ok)
            continue;
        scene.polygons.push_back(radiosity::makePolygon(corners, f.object, Rgb::gray(0.5)));
    }
    return scene;
}

// n points spread over the faces by area, each on its face.
std::vector<radiosity::SkyPoint> pointsOn(const radiosity::Scene& scene, int n) {
    std::vector<double> cumulative;
    double total = 0;
    for (const radiosity::Polygon& p : scene.polygons) cumulative.push_back(total += p.area);
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<radiosity::SkyPoint> points;
    for (int i = 0; i < n; ++i) {
        const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), u(rng) * total);
        const int f = static_cast<int>(
            std::min<ptrdiff_t>(it - cumulative.begin(), std::ssize(cumulative) - 1));
        const radiosity::Polygon& p = scene.polygons[static_cast<size_t>(f)];
        points.push_back({radiosity::pointOnPolygon(p, u(rng), u(rng)), p.normal, f});
    }
    return points;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <courtyard_dir> [--points N] [--rays R1,R2,...]\n",
                     argv[0]);
        return 2;
    }
    const std::string data = argv[1];
    int points = 76800;  // a transfer vector per pixel at 320x240
    std::string rays = "64,256,1024";
    for (int i = 2; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--points") == 0) points = std::atoi(argv[i + 1]);
        if (std::strcmp(argv[i], "--rays") == 0) rays = argv[i + 1];
    }
    std::printf("command: %s %s --points %d --rays %s\n", argv[0], data.c_str(), points,
                rays.c_str());

    std::printf("\n1. turning the sky: rotate + per-pixel 9-term dot product (RGB)\n");
    benchTurn(320, 240);
    benchTurn(1280, 960);

    const radiosity::Scene scene = loadGeometry(data + "/courtyard.obj");
    const radiosity::Visibility vis(scene);
    const std::vector<radiosity::SkyPoint> pts = pointsOn(scene, points);
    std::printf("\n2. transfer vectors: %d points on the courtyard (%zu faces), %d threads\n",
                points, scene.polygons.size(), tbb::this_task_arena::max_concurrency());
    std::stringstream list(rays);
    for (std::string r; std::getline(list, r, ',');) {
        const int k = radiosity::strataSide(std::atoi(r.c_str()));
        const auto t0 = radiosity::Clock::now();
        const std::vector<Sh9> T =
            radiosity::skyTransfers(vis, scene.bounds(), pts, {.rays = k * k});
        const double s = radiosity::secondsSince(t0);
        double open = 0;  // mean T00 / (pi c0): the share of the sky the points see
        for (const Sh9& t : T) open += t[0] / (3.14159265358979323846 * 0.28209479177387814);
        std::printf("  %5d rays: %8.3f s  (%.1f M rays/s; mean open sky %.3f)\n", k * k, s,
                    1e-6 * static_cast<double>(points) * k * k / s, open / points);
    }
    return 0;
}
