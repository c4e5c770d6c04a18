// relight eval <scene_dir> <edit_name> <image> [--error-map file]
#include "relight/cli/commands.h"

#include <cstdio>
#include <filesystem>

#include "relight/display/metric.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"

namespace relight::cli {

namespace fs = std::filesystem;

int runEval(const std::string& sceneDir, const std::string& edit, const std::string& image,
            const std::string& errorMapFile) {
    const fs::path dir(sceneDir);
    const SceneFile sf = loadScene(dir);
    if (sf.photos.empty())
        throw InputError((dir / "scene.json").string() + ": key \"photos\": eval needs a photo");
    const fs::path photo = sf.photos.front().file;
    fs::path photoMask = photo;
    photoMask.replace_extension(".mask.png");
    Image R = readImage(image);
    Image T = readImage(dir / "truth" / (edit + ".exr"));
    Image P = readImage(photo, sf.photos.front().encoding == PhotoSpec::Encoding::srgb);
    int w = 0, h = 0, w2 = 0, h2 = 0;
    auto mT = readMask(dir / "truth" / (edit + ".mask.png"), w, h);
    auto mP = readMask(photoMask, w2, h2);
    if (R.width != T.width || R.height != T.height)
        throw InputError(image + ": image is " + std::to_string(R.width) + "x" +
                         std::to_string(R.height) + ", the truth is " + std::to_string(T.width) +
                         "x" + std::to_string(T.height));
    Image errorMap;
    const Score s = scoreImage(R, T, P, mT, mP, errorMapFile.empty() ? nullptr : &errorMap);
    Image identity = readImage(dir / "truth" / "identity.exr");
    auto mI = readMask(dir / "truth" / "identity.mask.png", w, h);
    const Score floor = scoreImage(P, identity, P, mI, mP);
    std::printf("rel_rmse %.4f\n", s.relRmse);
    if (s.hasChanged)
        std::printf("changed_rel_rmse %.4f (%d of %d blocks)\n", s.changedRelRmse, s.changedBlocks,
                    s.blocks);
    else
        std::printf("changed_rel_rmse undefined (no block changes)\n");
    std::printf("noise_floor %.4f\n", floor.relRmse);
    if (!errorMapFile.empty()) {
        writeImage(errorMapFile, errorMap);
        std::printf("wrote %s (%dx%d blocks, block RMS error / mean truth)\n", errorMapFile.c_str(),
                    errorMap.width, errorMap.height);
    }
    return 0;
}

}  // namespace relight::cli
