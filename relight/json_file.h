// Writing a JSON document to a file atomically (reports, debug-view indexes).
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <system_error>

namespace relight {

/// Writes `j` to `path` through a temporary file renamed over it: a failed write never
/// leaves a half-written file. Throws std::runtime_error naming the file.
inline void writeJsonAtomic(const std::filesystem::path& path, const nlohmann::json& j) {
    namespace fs = std::filesystem;
    const fs::path tmp = path.parent_path() / (".tmp-" + path.filename().string());
    {
        std::ofstream out(tmp);
        out << j.dump(2) << "\n";
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

}  // namespace relight
