// Preparation and edit time against the photo's size: the bundled room with its photo at
// 320x240, resampled to 1280x960 and to 4000x3000 (12 MP), on 2 threads.
//
//   ./build/bench/photo_size data [--sizes 320x240,1280x960,4000x3000] [--edits 24]
//                                 [--epsilon E] [--keep DIR]
//
// For each size it writes a copy of data/room into a temporary directory: scene.json with
// the camera's size and intrinsics scaled (f and the principal point, whose pixel-centre
// convention puts it at (c + 0.5) s - 0.5, as /work/shared/tools/tessellate.py --upscale
// does), the photos resampled with OpenImageIO (ImageBufAlgo::resize, its default filter),
// the edits and objects copied; no truth. Then a child process (this program again, with
// --one) prepares it and prints, so that each size's peak memory (getrusage maxrss) is its own:
//   - the preparation's time, split by step (PreparedImage::times; "load and other" is the
//     rest: the photo's reading and checks, the scene);
//   - the sampling plan (item-buffer samples per pixel, pixel stride of the estimates);
//   - the time of a light edit, display included, median and 90th percentile over the
//     edits: the room's five light edits and random scalings of its four lights, each
//     rendered into an image reused from edit to edit (a viewer's framebuffer), and the
//     median of the same rendered into a fresh image (renderEdit's returning form); the
//     same edits in the per-pixel display (relight render's default, DisplayMode::pixel),
//     so that the preparation measures the direct light per pixel too;
//   - the time of taking the table out, then the cabinet against its two walls
//     (relight/dynamic/object_removal.h), of bringing each back, and the per-pixel frame;
//   - the peak resident memory of the child.
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_util.h"
#include "radiosity/stopwatch.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/relighting.h"

using namespace relight;
using radiosity::Clock;
using radiosity::secondsSince;
namespace fs = std::filesystem;

namespace {

/// data/room copied to `dst` at width x height: camera and photos scaled, no truth.
void writeScaledRoom(const fs::path& src, const fs::path& dst, int width, int height) {
    fs::remove_all(dst);
    fs::create_directories(dst);
    for (const auto& e : fs::directory_iterator(src)) {
        const std::string name = e.path().filename().string();
        if (name == "truth" || name == ".relight") continue;
        fs::copy(e.path(), dst / name, fs::copy_options::recursive);
    }
    nlohmann::json scene;
    std::ifstream(dst / "scene.json") >> scene;
    auto& cam = scene["camera"];
    const double sx = static_cast<double>(width) / cam["width"].get<int>();
    const double sy = static_cast<double>(height) / cam["height"].get<int>();
    cam["width"] = width;
    cam["height"] = height;
    auto& K = cam["K"];
    K[0][0] = K[0][0].get<double>() * sx;
    K[1][1] = K[1][1].get<double>() * sy;
    K[0][2] = (K[0][2].get<double>() + 0.5) * sx - 0.5;
    K[1][2] = (K[1][2].get<double>() + 0.5) * sy - 0.5;
    std::ofstream(dst / "scene.json") << scene.dump(1);
    for (const auto& ph : scene["photos"]) {
        const std::string file = (dst / ph["file"].get<std::string>()).string();
        OIIO::ImageBuf in(file);
        if (!in.read(0, 0, true, OIIO::TypeDesc::FLOAT))
            throw std::runtime_error(file + ": " + in.geterror());
        if (in.spec().width == width && in.spec().height == height) continue;
        OIIO::ImageSpec spec = in.spec();
        spec.width = spec.full_width = width;
        spec.height = spec.full_height = height;
        OIIO::ImageBuf out(spec);
        if (!OIIO::ImageBufAlgo::resize(out, in) || !out.write(file))
            throw std::runtime_error(file + ": cannot resize: " + out.geterror());
    }
}

double maxRssMiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

/// The child: prepare the scene in `dir`, time the edits, print one block.
int runOne(const std::string& dir, int edits, double epsilon) {
    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.epsilon = epsilon;
    o.pixelLight = true;  // relight's default: both displays can be timed
    auto t0 = Clock::now();
    const auto r = prepareRelighting(loadScene(dir), o);
    const double tPrepare = secondsSince(t0);
    const PreparedImage& P = r->prepared;
    const PrepareTimes& t = P.times;
    const double steps = t.itemBuffer + t.solve + t.reflectance + t.refinement + t.responses +
                         t.vertexLighting + t.shadowRemoval + t.displayMap;
    const double rssPrepared = maxRssMiB();
    std::printf("== %dx%d (%.1f MP): prepare %.2f s, peak memory %.0f MiB\n", P.photo.width,
                P.photo.height, P.photo.width * P.photo.height / 1e6, tPrepare, rssPrepared);
    std::printf(
        "   sampling: %d samples per pixel, estimates on the pixel sub-grid of stride %d; "
        "%d leaves, %zu vertices, %zu (pixel, vertex) pairs\n",
        r->sampling.spp, r->sampling.stride, P.leaves, P.vertexCount(), P.display.vertex.size());
    std::printf("   steps: %s, load and other %.3f s\n", stepTimes(t).c_str(), tPrepare - steps);

    // Edits: the room's light edits, then random scalings of each light in [0, 2].
    std::vector<std::vector<radiosity::Rgb>> radiance;
    for (const char* name :
         {"identity", "back_off", "left_off_right_double", "right_off_left_double", "colours"})
        radiance.push_back(editRadiance(
            r->scene, loadEdit(dir + "/edits/" + name + ".json", r->scene), P.photoRadiance));
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> scale(0.0, 2.0);
    while (static_cast<int>(radiance.size()) < edits) {
        std::vector<radiosity::Rgb> L = P.photoRadiance;
        for (auto& l : L) l = l * scale(rng);
        radiance.push_back(L);
    }
    Image out;
    renderEdit(P, radiance[0], out);  // the image's first allocation is not an edit's
    std::vector<double> reused, fresh;
    for (const auto& L : radiance) {
        const auto t1 = Clock::now();
        renderEdit(P, L, out);
        reused.push_back(secondsSince(t1));
    }
    for (size_t i = 0; i < radiance.size() && i < 10; ++i) {
        const auto t1 = Clock::now();
        const Image img = renderEdit(P, radiance[i]);
        fresh.push_back(secondsSince(t1));
    }
    std::printf(
        "   edit (%zu edits, display included, image reused): median %.1f ms, p90 %.1f "
        "ms; into a fresh image: median %.1f ms\n",
        radiance.size(), bench::quantile(reused, 0.5) * 1e3, bench::quantile(reused, 0.9) * 1e3,
        bench::quantile(fresh, 0.5) * 1e3);
    std::vector<double> perPixel;
    for (const auto& L : radiance) {
        const auto t1 = Clock::now();
        renderEdit(P, L, out, DisplayMode::pixel);
        perPixel.push_back(secondsSince(t1));
    }
    std::printf("   edit in the per-pixel display (image reused): median %.1f ms, p90 %.1f ms\n",
                bench::quantile(perPixel, 0.5) * 1e3, bench::quantile(perPixel, 0.9) * 1e3);
    // Every lamp at 10 times its radiance: every pixel's reflectance pooled, from the widest
    // pool (its worst case).
    {
        std::vector<radiosity::Rgb> L = P.photoRadiance;
        for (auto& l : L) l = l * 10.0;
        std::vector<double> bright;
        for (int k = 0; k < 5; ++k) {
            const auto t1 = Clock::now();
            renderEdit(P, L, out, DisplayMode::pixel);
            bright.push_back(secondsSince(t1));
        }
        std::printf(
            "   every lamp x10 in the per-pixel display (every pixel pooled): median %.1f ms\n",
            bench::quantile(bright, 0.5) * 1e3);
    }
    // The same without the pooled reflectance (pixel_light.h), in this run: its cost.
    PhotoPixels pool = std::move(r->prepared.photoPixels);
    r->prepared.photoPixels = {};
    std::vector<double> unpooled;
    for (const auto& L : radiance) {
        const auto t1 = Clock::now();
        renderEdit(P, L, out, DisplayMode::pixel);
        unpooled.push_back(secondsSince(t1));
    }
    r->prepared.photoPixels = std::move(pool);
    std::printf("   the same without the pooled reflectance: median %.1f ms, p90 %.1f ms\n",
                bench::quantile(unpooled, 0.5) * 1e3, bench::quantile(unpooled, 0.9) * 1e3);
    std::printf("   peak memory after the edits: %.0f MiB\n", maxRssMiB());

    // Taking the table out (Loscos et al. 1999, §5.3; their 0.7-2.9 s) and bringing it back,
    // 3 times: the solver's update, the fill (rays, texture synthesis, direct light at the
    // revealed samples) and the per-pixel display's first frame.
    for (const char* object : {"table", "cabinet"}) {
        std::vector<double> removal, fill, frame, back;
        int filled = 0;
        DynamicRelighting dyn(*r, P.photoRadiance);
        for (int k = 0; k < 3; ++k) {
            const auto t1 = Clock::now();
            dyn.removeObject(object);
            removal.push_back(secondsSince(t1));
            fill.push_back(dyn.times().fill);
            filled = dyn.removedRegion().filled + dyn.removedRegion().modelled;
            const auto t2 = Clock::now();
            const Image img = dyn.render(DisplayMode::pixel);
            frame.push_back(secondsSince(t2));
            const auto t3 = Clock::now();
            dyn.removeLast();
            back.push_back(secondsSince(t3));
        }
        std::printf(
            "   removing the %s (%d pixels filled): median %.3f s (the fill %.3f s), then the "
            "per-pixel frame %.3f s; bringing it back %.3f s\n",
            object, filled, bench::quantile(removal, 0.5), bench::quantile(fill, 0.5),
            bench::quantile(frame, 0.5), bench::quantile(back, 0.5));
    }
    std::fflush(stdout);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string data, sizes = "320x240,1280x960,4000x3000", keep, one;
    int edits = 24;
    double epsilon = RelightOptions{}.epsilon;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
            return argv[++i];
        };
        try {
            if (a == "--sizes")
                sizes = next();
            else if (a == "--edits")
                edits = std::stoi(next());
            else if (a == "--epsilon")
                epsilon = std::stod(next());
            else if (a == "--keep")
                keep = next();
            else if (a == "--one")
                one = next();
            else if (data.empty() && a.rfind("--", 0) != 0)
                data = a;
            else
                throw std::invalid_argument("unknown argument " + a);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "error: %s\n", e.what());
            return 2;
        }
    }
    try {
        if (!one.empty()) return runOne(one, std::max(edits, 20), epsilon);
        if (data.empty()) {
            std::fprintf(stderr,
                         "usage: %s <data_dir> [--sizes WxH,...] [--edits N] [--epsilon E] "
                         "[--keep DIR]\n",
                         argv[0]);
            return 2;
        }
        std::printf("command: %s %s --sizes %s --edits %d --epsilon %g\n", argv[0], data.c_str(),
                    sizes.c_str(), edits, epsilon);
        const fs::path root =
            keep.empty() ? fs::temp_directory_path() / ("photo_size." + std::to_string(getpid()))
                         : fs::path(keep);
        const std::string self = fs::read_symlink("/proc/self/exe").string();
        std::string list = sizes;
        int status = 0;
        while (!list.empty()) {
            const size_t comma = list.find(',');
            const std::string size = list.substr(0, comma);
            list = comma == std::string::npos ? "" : list.substr(comma + 1);
            int w = 0, h = 0;
            if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0)
                throw std::invalid_argument("--sizes: " + size + " is not WxH");
            const fs::path dir = root / ("room-" + size);
            auto t0 = Clock::now();
            writeScaledRoom(fs::path(data) / "room", dir, w, h);
            std::printf("\n(scene %s written in %.1f s)\n", dir.c_str(), secondsSince(t0));
            std::fflush(stdout);
            char eps[32];
            std::snprintf(eps, sizeof eps, "%.17g", epsilon);
            const std::string cmd = "'" + self + "' --one '" + dir.string() + "' --edits " +
                                    std::to_string(edits) + " --epsilon " + eps;
            if (std::system(cmd.c_str()) != 0) status = 1;
        }
        if (keep.empty()) fs::remove_all(root);
        return status;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
