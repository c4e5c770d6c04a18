// Writing a JSON file atomically (reports, debug-view indexes, edits).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "relight/io/atomic_write.h"

namespace relight {

/// writeTextAtomic() of `j` (2-space indented). The text is made before the file is opened,
/// so a document that cannot be dumped (invalid UTF-8) leaves no temporary file behind.
inline void writeJsonAtomic(const std::filesystem::path& path, const nlohmann::json& j) {
    writeTextAtomic(path, j.dump(2) + "\n");
}

}  // namespace relight
