// `relight import colmap`: a scene package (docs/scene-format.md) from a COLMAP
// reconstruction: one image's camera and pose, its photo (undistorted when its camera has a
// lens distortion), a mesh, and the real lights from a JSON file, or none.
//
// Everything is read and checked before anything is written, so a bad input leaves the
// output folder as it was: the model (relight/io/colmap_model.h), the image's camera
// (relight/io/colmap_camera.h), the photo's size against its camera, the lights (messages
// name the lights file and key), and the scene as a whole with the scene loader (the mesh
// must load, the lights must not clash with its objects). Then the mesh and the photo are
// copied (or linked) into the folder and scene.json is written last, atomically.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "relight/pipeline/camera.h"

namespace relight {

struct ColmapImportOptions {
    std::filesystem::path sparseDir;  ///< the COLMAP model's folder (text or binary)
    std::string image;                ///< NAME as the model has it (may hold sub-folders)
    std::filesystem::path imagesDir;  ///< COLMAP's image folder: the photo is imagesDir/NAME
    std::filesystem::path mesh;       ///< OBJ, PLY or glTF (relight/io/mesh_reader.h)
    /// The format's "lights" array: a file holding the array itself, or a JSON object with a
    /// "lights" key (another scene.json). Empty: no lights.
    std::filesystem::path lights;
    /// The format's "objects" settings, likewise (the object itself or an object with an
    /// "objects" key). Empty: none.
    std::filesystem::path objects;
    std::filesystem::path output;  ///< the scene folder to write
    /// The lights on in the photo (default: all of them).
    std::optional<std::vector<std::string>> lightsOn;
    std::optional<double> averageReflectance;
    std::string encoding;  ///< "linear", "srgb", or empty: from the photo's file type
    bool link = false;     ///< symbolic links to the photo and the mesh instead of copies
    bool force = false;    ///< write into a folder that is not empty
};

struct ColmapImportResult {
    std::filesystem::path modelFile;  ///< the images file the image came from
    std::string cameraModel;          ///< COLMAP's model name of the image's camera
    Camera camera;                    ///< as written into scene.json
    /// The undistorted photo's focal length over the distorted one's (1 when the camera
    /// is a pinhole: the photo is then copied as it is).
    double focalScale = 1;
    bool undistorted = false;
    std::filesystem::path photo, sceneJson;
    size_t lights = 0;
    std::vector<std::string> warnings;  ///< the scene loader's documented repairs
};

/// Imports (see above). Throws InputError for bad input, naming the file and line or key,
/// and OutputError when the output folder cannot be written or is not empty without
/// `force`.
ColmapImportResult importColmap(const ColmapImportOptions& options);

}  // namespace relight
