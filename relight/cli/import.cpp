// relight import colmap SPARSE_DIR --image NAME --images DIR --mesh FILE [--lights FILE]
//                       -o SCENE_DIR [--objects FILE] [--lights-on A,B] [--link] [--force]
// relight export colmap SCENE_DIR -o SPARSE_DIR [--binary] [--name NAME]
#include <cstdio>
#include <filesystem>

#include "relight/io/colmap_camera.h"
#include "relight/io/colmap_model.h"

#include "relight/cli/commands.h"
#include "relight/cli/util.h"

namespace relight::cli {

int runImportColmap(const ColmapImportOptions& options) {
    const auto start = Clock::now();
    const ColmapImportResult r = importColmap(options);
    for (const std::string& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    const Camera& c = r.camera;
    std::printf("image \"%s\" from %s: camera %s, %dx%d\n", options.image.c_str(),
                r.modelFile.string().c_str(), r.cameraModel.c_str(), c.width, c.height);
    if (r.undistorted)
        std::printf("undistorted into a pinhole photo, focal length x %.4f: %s\n", r.focalScale,
                    r.photo.string().c_str());
    std::printf("K: fx %.6g fy %.6g cx %.6g cy %.6g (pixel centres at integers)\n", c.fx, c.fy,
                c.cx, c.cy);
    std::printf("%zu light%s\n", r.lights, r.lights == 1 ? "" : "s");
    std::printf("wrote %s (%.2f s)\n", r.sceneJson.string().c_str(), secondsSince(start));
    return 0;
}

}  // namespace relight::cli

namespace relight::cli {

int runExportColmap(const ExportColmapArgs& a) {
    const SceneFile sf = loadScene(a.scene);
    std::string name = a.name;
    if (name.empty())
        name = sf.photos.empty() ? "photo.png" : sf.photos.front().file.filename().string();
    colmap::Model model;
    model.cameras[1] = colmap::colmapCamera(sf.camera, 1);
    model.images.push_back(colmap::colmapImage(sf.camera, 1, 1, name));
    std::error_code ec;
    std::filesystem::create_directories(a.output, ec);
    if (ec) throw OutputError(a.output + ": cannot create the folder: " + ec.message());
    a.binary ? colmap::writeBinary(a.output, model) : colmap::writeText(a.output, model);
    std::printf("wrote %s/%s: camera 1 (PINHOLE %dx%d), image 1 \"%s\"\n", a.output.c_str(),
                a.binary ? "cameras.bin, images.bin" : "cameras.txt, images.txt", sf.camera.width,
                sf.camera.height, name.c_str());
    return 0;
}

}  // namespace relight::cli
