// A COLMAP sparse model's cameras and images (COLMAP's "Output format" documentation), read
// from its text files (cameras.txt, images.txt) or its binary files (cameras.bin,
// images.bin), and written in either form (the tests' and benchmarks' round trips).
//
// COLMAP's conventions are kept as the files have them, on purpose: the conversion to the
// scene format's camera is one place (relight/io/colmap_camera.h), not spread over readers.
//   - an image's (qvec, tvec) is world-to-camera: x_cam = R(q) x_world + t, the quaternion
//     Hamilton's, w first;
//   - a camera's principal point is in COLMAP's pixel coordinates, where the centre of the
//     top-left pixel is (0.5, 0.5).
// The 2D points and 3D points are not read (the relighting needs the mesh, not the points).
//
// Every problem is an InputError naming the file and the line (text) or the byte offset
// and the record (binary): "sparse/images.txt:14: image 3 uses camera 9, which
// sparse/cameras.txt does not define".
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace relight::colmap {

/// One line of cameras.txt or one record of cameras.bin.
struct Camera {
    int64_t id = 0;
    std::string model;  ///< COLMAP's model name: "PINHOLE", "SIMPLE_RADIAL", ...
    int64_t width = 0, height = 0;
    std::vector<double> params;  ///< in COLMAP's order for the model (colmap_camera.h)
    std::string where;           ///< "<file>:<line>" or "<file>: camera record <k>"
};

/// One image of images.txt or images.bin (its 2D points skipped).
struct Image {
    int64_t id = 0;
    std::array<double, 4> qvec{1, 0, 0, 0};  ///< world-to-camera rotation, w x y z
    std::array<double, 3> tvec{0, 0, 0};     ///< world-to-camera translation
    int64_t cameraId = 0;
    std::string name;   ///< the photo's path relative to COLMAP's image folder
    std::string where;  ///< "<file>:<line>" or "<file>: image record <k>"
};

struct Model {
    std::map<int64_t, Camera> cameras;
    std::vector<Image> images;  ///< in the file's order
    std::filesystem::path camerasFile, imagesFile;

    /// The image named `name`. Throws InputError naming imagesFile (and a few of the
    /// names it holds) when there is none.
    const Image& image(const std::string& name) const;
    /// The camera of `image`. Throws InputError naming the image's line when its camera id
    /// is not defined in camerasFile.
    const Camera& cameraOf(const Image& image) const;
};

/// The number of parameters of a COLMAP camera model, by name or by model id; -1 for a
/// name or id COLMAP does not define. Ids and counts follow COLMAP's camera_models.h.
int paramCount(const std::string& model);
int modelId(const std::string& model);  ///< -1 when unknown
std::string modelName(int id);          ///< "" when unknown

/// Reads <dir>/cameras.txt and <dir>/images.txt.
Model readText(const std::filesystem::path& dir);
/// Reads <dir>/cameras.bin and <dir>/images.bin (little-endian, as COLMAP writes them).
Model readBinary(const std::filesystem::path& dir);
/// The binary model when <dir> has cameras.bin and images.bin, else the text model (COLMAP's
/// own rule). Throws InputError naming the folder when it holds neither, and a numbered
/// subfolder (COLMAP's sparse/0) that does.
Model readModel(const std::filesystem::path& dir);

/// Writes <dir>/cameras.txt and <dir>/images.txt (17 significant digits, each image with
/// an empty 2D points line). The folder must exist. Throws OutputError.
void writeText(const std::filesystem::path& dir, const Model& model);
/// Writes <dir>/cameras.bin and <dir>/images.bin (no 2D points). Throws OutputError.
void writeBinary(const std::filesystem::path& dir, const Model& model);

}  // namespace relight::colmap
