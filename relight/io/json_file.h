// Writing a text or JSON file atomically (reports, debug-view indexes, edits, OBJ files).
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <system_error>

namespace relight {

/// Writes `text` to `path` through a temporary file renamed over it: a failed write never
/// leaves a half-written file. Throws std::runtime_error naming the file.
inline void writeTextAtomic(const std::filesystem::path& path, const std::string& text) {
    namespace fs = std::filesystem;
    const fs::path tmp = path.parent_path() / (".tmp-" + path.filename().string());
    {
        std::ofstream out(tmp);
        out << text;
        out.close();  // a write that fails on flushing (disk full) fails here, not silently
        if (!out) {
            std::error_code ec;
            fs::remove(tmp, ec);
            throw std::runtime_error(path.string() + ": cannot write");
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw std::runtime_error(path.string() + ": cannot write: " + ec.message());
    }
}

/// writeTextAtomic() of `j` (2-space indented). The text is made before the file is opened,
/// so a document that cannot be dumped (invalid UTF-8) leaves no temporary file behind.
inline void writeJsonAtomic(const std::filesystem::path& path, const nlohmann::json& j) {
    writeTextAtomic(path, j.dump(2) + "\n");
}

}  // namespace relight
