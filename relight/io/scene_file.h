// Scene package loading: scene.json + geometry + lights, exactly as specified in
// docs/scene-format.md ("relight-scene/1"). Geometry may also be PLY or glTF
// (an extension of the spec, relight/io/mesh_reader.h).
//
// Every problem with the input is reported as an InputError whose message names the file
// and the line (OBJ), the mesh and face (PLY, glTF) or the JSON key path (scene.json), e.g.
//   "data/room/room.obj:12: face references vertex 40, but only 36 are defined".
// Documented repairs, each reported as a warning (SceneFile::warnings):
//   - a non-planar quad is split into two triangles along its shorter diagonal;
//   - a non-convex planar quad is split into two triangles along the diagonal that
//     keeps both halves convex;
//   - a convex planar face with more than 4 vertices is split into a fan of triangles;
//   - a degenerate face (zero area, repeated vertices) is dropped.
// Then the geometry's polygons are cut where another surface stands across them (a wall on
// a slab that runs on beneath it: radiosity/contact_split.h), so that no element of the
// solution straddles a wall and leaks light through it; the faces then wholly inside closed
// solids (a slab's piece under a wall, the walls' touching ends: radiosity/buried.h) are left
// out. The counts are a line of the commands' progress (contactSplitLine()), not a warning:
// every surface light can reach or the camera can see stays as the file has it.
// Non-finite coordinates, faces with fewer than 3 vertices, bad indices, zero-area or
// non-planar lights, negative radiance, unknown JSON keys and missing files are errors.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "radiosity/contact_split.h"
#include "radiosity/scene.h"
#include "relight/errors.h"
#include "relight/pipeline/camera.h"

namespace relight {

using radiosity::Rgb;

struct PhotoSpec {
    std::filesystem::path file;  ///< absolute or relative to the working directory
    enum class Encoding { linear, srgb } encoding = Encoding::linear;
    std::vector<std::string> lightsOn;  ///< names of the real lights on in this photo
};

struct ObjectSettings {
    std::optional<Rgb> reflectance;  ///< used where the photo does not see the object
    bool removable = false;
};

struct SceneFile {
    std::filesystem::path dir;  ///< the scene folder
    radiosity::Scene scene;     ///< geometry + emitting faces of the lights
    Camera camera;
    std::vector<PhotoSpec> photos;                         ///< may be empty
    std::map<std::string, ObjectSettings> objectSettings;  ///< from "objects"
    std::optional<double> averageReflectance;              ///< the user's guess, in [0, 1)
    /// Per light (same index as scene.lights): radiance given in scene.json
    /// (photo units); zero where it is "estimate".
    std::vector<Rgb> nominalRadiance;
    /// Per light: true when scene.json says "estimate" for its strength (a quad's "radiance",
    /// a sun's "irradiance", each of a sky's 9 components for its "sh9").
    std::vector<bool> estimateRadiance;
    std::vector<std::string> warnings;  ///< documented repairs, with file and line
    /// The geometry's polygons cut where other surfaces meet them (radiosity/contact_split.h),
    /// and the seconds it took: a line of the commands' progress (contactSplitLine()).
    radiosity::ContactSplitReport contactSplit;
    double contactSplitSeconds = 0;
    /// The geometry's faces inside closed solids, left out after the cut (radiosity/buried.h):
    /// how many, their area (m^2) and the seconds the search took (contactSplitLine()).
    int buriedPolygons = 0;
    double buriedArea = 0;
    double buriedSeconds = 0;
    /// The geometry files of "geometry", in scene.json's order (dir / name), each followed
    /// by the files it drew on (a .gltf's buffers): with scene.json and the photos, the
    /// files the scene's content comes from (relight/io/prepared_cache.h).
    std::vector<std::filesystem::path> geometryFiles;

    /// Lights' on/off state in the first photo: scene.lights[i].radiance is
    /// nominalRadiance[i] when the light is in photos[0].lightsOn (or when there is no
    /// photo), zero otherwise. loadScene() leaves the scene in this state.
    void setPhotoLightState();
    /// Whether light `i` is on in the first photo (in its lights_on; every light is on
    /// when there is no photo).
    bool lightOnInPhoto(size_t i) const;
};

/// A copy of `sf` without its polygons, everything else as it is: what a command keeps of
/// the scene (its lights, camera, names) while the preparation takes the polygons, which are
/// the scene's bulk (168 bytes a face: 1 GB for a 6 M-face mesh). `sf` is left as it was.
SceneFile copyWithoutPolygons(SceneFile& sf);

/// "geometry: N polygons cut along M lines where other surfaces meet them (K pieces added),
/// T s", followed by "; F faces inside solids left out (A m^2), T s" when some were; empty
/// when nothing was cut or left out.
std::string contactSplitLine(const SceneFile& sf);

/// A photo's encoding from its file's extension: .exr, .hdr, .pfm linear; .png, .jpg, .jpeg
/// sRGB; `known` false (and linear) for any other.
PhotoSpec::Encoding encodingFromExtension(const std::filesystem::path& file, bool& known);

/// Loads <dir>/scene.json and the files it names. Reflectance of each polygon: the
/// object's "reflectance" when given, else average_reflectance (grey), else 0.5; emitting
/// faces have reflectance 0. Throws InputError.
SceneFile loadScene(const std::filesystem::path& dir);

/// loadScene() with scene.json's text read from `sceneJson` rather than from
/// <dir>/scene.json (messages still name that file); the files it names are looked up in
/// `dir` as loadScene() does. Lets the JSON reading be driven from memory (fuzz/).
SceneFile parseScene(std::istream& sceneJson, const std::filesystem::path& dir);

}  // namespace relight
