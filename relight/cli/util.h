// Small helpers shared by the subcommands: timing and JSON reports.
#pragma once

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "radiosity/rgb.h"

namespace relight::cli {

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

inline nlohmann::json rgbJson(const radiosity::Rgb& c) {
    return {c.r, c.g, c.b};
}

/// Writes `j` to `path` through a temporary file renamed over it: a failed write never
/// leaves a half-written report.
inline void writeJsonAtomic(const std::string& path, const nlohmann::json& j) {
    namespace fs = std::filesystem;
    const fs::path tmp =
        fs::path(path).parent_path() / (".tmp-" + fs::path(path).filename().string());
    {
        std::ofstream out(tmp);
        out << j.dump(2) << "\n";
        if (!out) throw std::runtime_error(path + ": cannot write report");
    }
    fs::rename(tmp, path);
}

}  // namespace relight::cli
