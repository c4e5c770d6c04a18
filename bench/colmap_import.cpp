// Import times of `relight import colmap` (relight/io/colmap_import.h):
//   1. a model of N images (default 1000), each with P 2D points (default 2000, about what
//      COLMAP keeps per image of a room), in text and in binary: reading the model alone,
//      and the whole import of one of its images (the room's camera, photo, mesh, lights);
//   2. a 12 MP (4000x3000) 8-bit JPEG through a SIMPLE_RADIAL camera: the whole import,
//      and its steps (the pinhole fit, the resampling; the rest is reading and writing).
// Prints each figure (best of 5) and the command that made it.
//   ./build/bench/colmap_import data [--images N] [--points P]
#include <OpenImageIO/imageio.h>

#include <unistd.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <thread>

#include "radiosity/stopwatch.h"
#include "relight/io/colmap_camera.h"
#include "relight/io/colmap_import.h"
#include "relight/io/colmap_model.h"
#include "relight/io/scene_file.h"
#include "relight/io/undistort.h"

namespace {

namespace fs = std::filesystem;
namespace colmap = relight::colmap;

/// The best of 5 runs of `f`, in seconds.
double bestOf5(const std::function<void()>& f) {
    double best = 1e300;
    for (int i = 0; i < 5; ++i) {
        const auto t0 = radiosity::Clock::now();
        f();
        best = std::min(best, radiosity::secondsSince(t0));
    }
    return best;
}

/// images.txt and images.bin of `images`, each with `points` 2D points (as COLMAP writes
/// them: a text line of X Y POINT3D_ID triples, binary records of 24 bytes).
void writeImagesWithPoints(const fs::path& dir, const std::vector<colmap::Image>& images,
                           int points) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> pixel(0, 320);
    std::FILE* text = std::fopen((dir / "text" / "images.txt").c_str(), "w");
    std::ofstream bin(dir / "bin" / "images.bin", std::ios::binary);
    auto put = [&](const auto& v) { bin.write(reinterpret_cast<const char*>(&v), sizeof(v)); };
    put(static_cast<uint64_t>(images.size()));
    std::fprintf(text, "# Image list with two lines of data per image:\n");
    for (const colmap::Image& im : images) {
        std::fprintf(text, "%lld %.17g %.17g %.17g %.17g %.17g %.17g %.17g %lld %s\n",
                     static_cast<long long>(im.id), im.qvec[0], im.qvec[1], im.qvec[2], im.qvec[3],
                     im.tvec[0], im.tvec[1], im.tvec[2], static_cast<long long>(im.cameraId),
                     im.name.c_str());
        put(static_cast<int32_t>(im.id));
        for (const double q : im.qvec) put(q);
        for (const double t : im.tvec) put(t);
        put(static_cast<int32_t>(im.cameraId));
        bin.write(im.name.c_str(), static_cast<std::streamsize>(im.name.size() + 1));
        put(static_cast<uint64_t>(points));
        for (int p = 0; p < points; ++p) {
            const double x = pixel(rng), y = pixel(rng);
            const int64_t id = p % 3 == 0 ? -1 : p;
            std::fprintf(text, p ? " %.2f %.2f %lld" : "%.2f %.2f %lld", x, y,
                         static_cast<long long>(id));
            put(x);
            put(y);
            put(id);
        }
        std::fprintf(text, "\n");
    }
    std::fclose(text);
}

/// The room's import options with the model in `sparse` and its photo in `images`.
relight::ColmapImportOptions roomImport(const fs::path& data, const fs::path& sparse,
                                        const fs::path& images, const std::string& name,
                                        const fs::path& out) {
    relight::ColmapImportOptions o;
    o.sparseDir = sparse;
    o.image = name;
    o.imagesDir = images;
    o.mesh = data / "room" / "room.obj";
    o.lights = data / "room" / "scene.json";
    o.output = out;
    o.force = true;
    return o;
}

void largeModel(const fs::path& data, const fs::path& work, int count, int points) {
    const relight::Camera room = relight::loadScene(data / "room").camera;
    colmap::Model model;
    model.cameras[1] = colmap::colmapCamera(room, 1);
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int i = 0; i < count; ++i) {
        relight::Camera c = room;
        if (i != count / 2) c.cameraFromWorldT += radiosity::Vec3(unit(rng), unit(rng), unit(rng));
        model.images.push_back(colmap::colmapImage(
            c, i + 1, 1, i == count / 2 ? "photo.exr" : "IMG_" + std::to_string(i) + ".jpg"));
    }
    for (const char* form : {"text", "bin"}) fs::create_directories(work / form);
    colmap::writeText(work / "text", model);
    colmap::writeBinary(work / "bin", model);
    writeImagesWithPoints(work, model.images, points);
    fs::create_directories(work / "images");
    fs::copy_file(data / "room" / "photo.exr", work / "images" / "photo.exr",
                  fs::copy_options::overwrite_existing);
    for (const char* form : {"text", "bin"}) {
        const double read = bestOf5([&] { colmap::readModel(work / form); });
        const double all = bestOf5([&] {
            relight::importColmap(
                roomImport(data, work / form, work / "images", "photo.exr", work / "out"));
        });
        std::printf(
            "%d images x %d points, %s model (%.1f MB): read %.3f s, whole import %.3f s\n", count,
            points, form,
            static_cast<double>(fs::file_size(
                work / form / (std::string("images.") + (form[0] == 't' ? "txt" : "bin")))) /
                1e6,
            read, all);
    }
}

void distortedPhoto(const fs::path& data, const fs::path& work) {
    const int w = 4000, h = 3000;
    const relight::Camera room = relight::loadScene(data / "room").camera;
    colmap::Model model;
    model.cameras[1] = {1, "SIMPLE_RADIAL", w, h, {3000, w / 2.0, h / 2.0, -0.05}, ""};
    model.images.push_back(colmap::colmapImage(room, 1, 1, "big.jpg"));
    fs::create_directories(work / "sparse12");
    colmap::writeText(work / "sparse12", model);
    // A grid on grey, as an 8-bit JPEG (what a camera writes).
    std::vector<uint8_t> px(static_cast<size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                px[(static_cast<size_t>(y) * w + x) * 3 + c] =
                    static_cast<uint8_t>(x % 100 < 4 || y % 100 < 4 ? 240 : 60 + 40 * c);
    fs::create_directories(work / "images12");
    auto out = OIIO::ImageOutput::create((work / "images12" / "big.jpg").string());
    OIIO::ImageSpec spec(w, h, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("Compression", "jpeg:95");
    if (!out || !out->open((work / "images12" / "big.jpg").string(), spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, px.data()) || !out->close()) {
        std::fprintf(stderr, "cannot write the 12 MP photo\n");
        std::exit(1);
    }
    const colmap::Lens lens = colmap::lensOf(model.cameras[1]);
    colmap::Lens pinhole;
    const double fit = bestOf5([&] { pinhole = relight::undistortedLens(lens, "bench"); });
    relight::PixelGrid grid{w, h, 3, std::vector<float>(static_cast<size_t>(w) * h * 3, 0.5f)};
    const double resample = bestOf5([&] { relight::undistortPixels(grid, lens, pinhole); });
    const double all = bestOf5([&] {
        relight::importColmap(
            roomImport(data, work / "sparse12", work / "images12", "big.jpg", work / "out12"));
    });
    std::printf(
        "12 MP SIMPLE_RADIAL JPEG (4000x3000, k -0.05): whole import %.2f s "
        "(pinhole fit %.3f s, bilinear resampling %.3f s, the rest reading the JPEG "
        "and writing the half-float EXR); focal length x %.4f\n",
        all, fit, resample, pinhole.fx / lens.fx);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <data_dir> [--images N] [--points P]\n", argv[0]);
        return 2;
    }
    const fs::path data = argv[1];
    int images = 1000, points = 2000;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--images") == 0) images = std::atoi(argv[i + 1]);
        if (std::strcmp(argv[i], "--points") == 0) points = std::atoi(argv[i + 1]);
    }
    std::printf("command: %s %s --images %d --points %d (%u hardware threads)\n", argv[0],
                data.c_str(), images, points, std::thread::hardware_concurrency());
    const fs::path work =
        fs::temp_directory_path() / ("colmap_import_bench_" + std::to_string(::getpid()));
    largeModel(data, work, images, points);
    distortedPhoto(data, work);
    fs::remove_all(work);
    return 0;
}
