// Fuzz target: COLMAP's model readers (relight::colmap::readText, readBinary), then the
// camera of each image as the import converts it (lensOf, sceneCamera). The first byte
// picks the file the other bytes are: cameras.txt, images.txt, cameras.bin or images.bin;
// the other file of the pair is a valid one (one PINHOLE camera, one image), so that the
// reader gets past it. The readers read files, so the bytes go to a folder of this
// process's own.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "relight/errors.h"
#include "relight/io/colmap_camera.h"
#include "relight/io/colmap_model.h"

namespace {

namespace fs = std::filesystem;
namespace colmap = relight::colmap;

/// This process's folder, removed at exit.
fs::path gDir;
void removeDir() {
    std::error_code ec;
    fs::remove_all(gDir, ec);
}

void write(const fs::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

/// The valid files (one camera, one image, as COLMAP writes them), written once by the
/// project's writer into `dir` and kept as bytes: at every input only the two files are
/// written again, with no model to make and no temporary file to rename.
std::string validFile(const fs::path& dir, const char* name) {
    static bool written = false;
    if (!written) {
        colmap::Model m;
        m.cameras[1] = {1, "PINHOLE", 320, 240, {170, 170, 160, 120}, ""};
        colmap::Image image;
        image.id = 1;
        image.qvec = {0.5976, 0.7205, 0.2707, -0.2245};
        image.tvec = {-2.88, 1.30, 2.54};
        image.cameraId = 1;
        image.name = "photo.exr";
        m.images.push_back(image);
        colmap::writeText(dir, m);
        colmap::writeBinary(dir, m);
        written = true;
    }
    std::ifstream in(dir / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path dir = [] {
        // In memory where there is a tmpfs: two files are written at every input.
        std::error_code ec;
        const fs::path base =
            fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
        const fs::path d = base / ("colmap_fuzz_" + std::to_string(getpid()));
        fs::create_directories(d);
        gDir = d;
        std::atexit(removeDir);
        return d;
    }();
    static const char* const kFiles[] = {"cameras.txt", "images.txt", "cameras.bin", "images.bin"};
    static const std::string kValid[] = {validFile(dir, kFiles[0]), validFile(dir, kFiles[1]),
                                         validFile(dir, kFiles[2]), validFile(dir, kFiles[3])};
    if (size == 0) return 0;
    const int which = data[0] % 4;
    const bool binary = which >= 2;
    const int other = binary ? 5 - which : 1 - which;  // the other file of the pair
    write(dir / kFiles[other], kValid[other]);
    write(dir / kFiles[which], std::string(reinterpret_cast<const char*>(data + 1), size - 1));
    try {
        const colmap::Model m = binary ? colmap::readBinary(dir) : colmap::readText(dir);
        for (const colmap::Image& image : m.images) {
            const colmap::Lens lens = colmap::lensOf(m.cameraOf(image));
            colmap::sceneCamera(image, lens);
        }
    } catch (const relight::InputError&) {
        // The documented answer to bad input; any other exception escapes and is a finding.
    }
    return 0;
}
