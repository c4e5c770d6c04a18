// One check for every file the engine reads (scene.json, edits, geometry, photos): it must
// be there and be a regular file. A directory fails to open in a confusing way, and a
// device or a pipe (a scene naming /dev/zero as its geometry) would be read without end.
#pragma once

#include <filesystem>
#include <string>

#include "relight/errors.h"

namespace relight {

/// Throws InputError naming `path` unless it is a regular file (or a link to one):
///   "<path>: <kind> not found", "<path>: is a directory, not <a kind>",
///   "<path>: is not a regular file (a device, a pipe or a socket)".
/// `kind` names what was expected ("OBJ file"), with its article in `aKind` ("an OBJ file").
inline void requireRegularFile(const std::filesystem::path& path, const std::string& kind,
                               const std::string& aKind) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status))
        throw InputError(path.string() + ": " + kind + " not found");
    if (std::filesystem::is_directory(status))
        throw InputError(path.string() + ": is a directory, not " + aKind);
    if (!std::filesystem::is_regular_file(status))
        throw InputError(path.string() +
                         ": is not a regular file (a device, a pipe or a socket): " + aKind +
                         " is expected");
}

}  // namespace relight
