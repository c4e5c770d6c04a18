// Edit saving: "relight-edit/1" as specified in docs/scene-format.md ("Edit"), the
// inverse of loadEdit() (edit_file.h). A viewer saves the user's session with it, and
// `relight render` renders the file later: loadEdit(writeEdit(edit)) gives the same lights,
// virtual lights and objects (the same OBJ files, the same numbers bit for bit) and removals.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "relight/io/edit_file.h"

namespace relight {

/// The edit as "relight-edit/1" JSON. Object files are written relative to `editFolder` (the
/// folder the JSON will be in; empty = the current folder), with forward slashes; lights:
/// a quad's {"scale": s} or {"radiance": [r, g, b]}; a sun's, point lamp's or sky's edit
/// (LightEdit::emitter) by the fields its light names (radiosity::editFields: "scale",
/// "irradiance", "intensity", "sh9", "direction", "position", "rotate"); add_lights with
/// "name", "type" and a quad's "vertices", "radiance", or the fields a sun, point lamp or
/// sky says it has (radiosity::Emitter::fields); add_objects with "name", "file", "reflectance",
/// "transform" (4x4 row-major); remove_objects. Empty parts are left out. Doubles survive the round
/// trip exactly (nlohmann::json dumps the shortest text that reads back as the same double). Throws
/// std::invalid_argument naming the key path for what the file could not say: a non-finite number
/// (JSON has none; it would be written as null), a quad's change with both or neither of scale and
/// radiance, an emitter's change without its light or saying nothing, an object without a file.
nlohmann::json editJson(const EditFile& edit, const std::filesystem::path& editFolder);

/// Writes editJson(edit, file.parent_path()) atomically (writeJsonAtomic). Throws
/// OutputError naming the file when it cannot be written (e.g. a missing folder), and
/// editJson's std::invalid_argument before touching it; nothing is left half-written.
void writeEdit(const std::filesystem::path& file, const EditFile& edit);

/// Writes a unit cube as OBJ: base centred on the origin at z = 0, x and y in [-0.5, 0.5],
/// z in [0, 1], faces wound so that their normals point outward (as data/room/objects/box.obj,
/// a 0.3 m cube of the same layout). Atomic like writeEdit. A viewer scales and places it
/// with the transform.
void writeUnitBoxObj(const std::filesystem::path& file);
/// The text writeUnitBoxObj() writes (a viewer parses it to place boxes in memory).
const char* unitBoxObjText();

}  // namespace relight
