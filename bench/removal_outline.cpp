// The outline around a removed real object (issue 34): the error against the path tracer's
// truth in bands of pixels at Chebyshev distance d = 1..6 from the pixels the object covered
// in the photo (any item-buffer sample on it), split into the band's pixels the removal
// replaced (the region's mask) and those it left to the display. A light outline shows as
// a positive signed error in the first bands. Default per-pixel display, default settings.
//
//   ./build/bench/removal_outline [SCENE_DIR] [--write DIR]     (default: data/room)
//
// --write DIR: DIR/<edit>.exr (the removal) and DIR/<edit>-region.png (0: outside, 128: the
// region's mask, 255: covered by the object).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/relighting.h"

using namespace relight;
namespace fs = std::filesystem;

namespace {

constexpr int kBands = 6;

struct Band {
    double abs = 0, signedSum = 0;
    int n = 0;
};

/// Chebyshev distance of each pixel to the nearest covered one (0 on them), up to kBands + 1.
std::vector<int> distanceToCovered(const RemovedRegion& g, int W, int H) {
    std::vector<int> d(static_cast<size_t>(W) * H, kBands + 1);
    for (int by = 0; by < g.height; ++by)
        for (int bx = 0; bx < g.width; ++bx) {
            if (!g.covered[static_cast<size_t>(by * g.width + bx)]) continue;
            const int x = g.x0 + bx, y = g.y0 + by;
            for (int dy = -kBands; dy <= kBands; ++dy)
                for (int dx = -kBands; dx <= kBands; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if (u < 0 || v < 0 || u >= W || v >= H) continue;
                    int& e = d[static_cast<size_t>(v) * W + u];
                    e = std::min(e, std::max(std::abs(dx), std::abs(dy)));
                }
        }
    return d;
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
    std::printf("command: ./build/bench/removal_outline %s%s\n", dir.c_str(),
                write.empty() ? "" : (" --write " + write.string()).c_str());
    RelightOptions options;
    options.pixelLight = true;  // relight render's default display
    auto r = prepareRelighting(loadScene(dir), options);
    const int W = r->items.width, H = r->items.height;
    std::printf(
        "bands: error / mean truth of the band (abs, signed), pixels; 'in' = the "
        "region's mask, 'out' = left to the display\n");
    for (const auto& entry : fs::directory_iterator(dir / "edits")) {
        const std::string edit = entry.path().stem().string();
        if (edit.rfind("remove_", 0) != 0 || !fs::exists(dir / "truth" / (edit + ".exr"))) continue;
        const EditFile e = loadEdit(entry.path(), r->scene);
        DynamicRelighting dyn(*r, editRadiance(r->scene, e, r->prepared.photoRadiance));
        for (const auto& object : e.removeObjects) dyn.removeObject(object);
        const Image image = dyn.render(DisplayMode::pixel);
        const Image truth = readImage(dir / "truth" / (edit + ".exr"));
        int mw = W, mh = H;
        const auto valid = readMask(dir / "truth" / (edit + ".mask.png"), mw, mh);
        const Score s = scoreImage(image, truth, r->prepared.photo, valid,
                                   readMask(dir / "photo.mask.png", mw, mh));
        const RemovedRegion& g = dyn.removedRegion();
        const std::vector<int> dist = distanceToCovered(g, W, H);
        Band in[kBands + 1], out[kBands + 1];
        double truthSum = 0;
        int truthN = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const size_t px = static_cast<size_t>(y) * W + x;
                const int d = dist[px];
                if (d < 1 || d > kBands || !valid[px]) continue;
                double a = 0, t = 0;
                for (int c = 0; c < 3; ++c) {
                    a += static_cast<double>(image.at(x, y)[c]);
                    t += static_cast<double>(truth.at(x, y)[c]);
                }
                Band& b = g.inMask(x, y) ? in[d] : out[d];
                b.abs += std::abs(a - t) / 3;
                b.signedSum += (a - t) / 3;
                ++b.n;
                truthSum += t / 3;
                ++truthN;
            }
        const double mean = truthN > 0 ? truthSum / truthN : 1.0;
        std::printf("%-16s rel_rmse %.4f / changed %.4f\n", edit.c_str(), s.relRmse,
                    s.changedRelRmse);
        for (int d = 1; d <= kBands; ++d) {
            const auto show = [&](const char* name, const Band& b) {
                if (b.n == 0) return std::printf("  %s      -      -     0", name);
                return std::printf("  %s %+6.3f %6.3f %5d", name, b.signedSum / b.n / mean,
                                   b.abs / b.n / mean, b.n);
            };
            Band all{in[d].abs + out[d].abs, in[d].signedSum + out[d].signedSum,
                     in[d].n + out[d].n};
            std::printf("  d=%d", d);
            show("all", all);
            show("in", in[d]);
            show("out", out[d]);
            std::printf("\n");
        }
        if (!write.empty()) {
            fs::create_directories(write);
            writeImage(write / (edit + ".exr"), image);
            Image region(W, H);
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const bool cov = dist[static_cast<size_t>(y) * W + x] == 0;
                    const float v = cov ? 1.0f : g.inMask(x, y) ? 0.2f : 0.0f;
                    for (int c = 0; c < 3; ++c) region.at(x, y)[c] = v;
                }
            writeImage(write / (edit + "-region.exr"), region);
        }
        std::fflush(stdout);
    }
    return 0;
}
