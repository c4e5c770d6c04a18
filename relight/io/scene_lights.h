// Real lamps placed on the photo (the viewer's "real lamps"), added to a scene's scene.json
// as the format's quad lights (docs/scene-format.md, "lights"), so that a scene imported
// without lights (relight import colmap) gets its lamps without writing JSON.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"

namespace relight {

/// The corners of a width x height rectangle centred on `centre` in the plane whose normal
/// is `normal`, counter-clockwise seen from the side `normal` points to (the side a quad
/// light emits to). Its edges run along the world x axis made perpendicular to the normal
/// (y when the normal is nearly x), so that a lamp on a wall or ceiling is square with the
/// room. `normal` need not be unit length but must not be zero.
std::vector<radiosity::Vec3> lampQuad(const radiosity::Vec3& centre, const radiosity::Vec3& normal,
                                      double width, double height);

/// A real lamp to add to scene.json.
struct RealLamp {
    std::string name;
    std::vector<radiosity::Vec3> corners;    ///< counter-clockwise from the side it emits to
    std::optional<radiosity::Rgb> radiance;  ///< none: "estimate" (from the photo)
    bool onInPhoto = true;                   ///< listed in the first photo's lights_on
};

/// Appends `lamps` to <dir>/scene.json's "lights" (and the names of those on in the photo to
/// its first photo's "lights_on"), keeping every other key as it is. The scene as it will be
/// is loaded first (scene_file.h), so a name already taken or a quad the format refuses is
/// an InputError naming scene.json and the key, and the file is left as it was; then it is
/// written atomically. Throws OutputError when it cannot be written.
void addLampsToScene(const std::filesystem::path& dir, const std::vector<RealLamp>& lamps);

}  // namespace relight
