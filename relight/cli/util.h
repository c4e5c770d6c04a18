// Small helpers shared by the subcommands: timing and JSON reports.
#pragma once

#include <chrono>
#include <nlohmann/json.hpp>
#include <string>

#include "radiosity/rgb.h"
#include "relight/io/json_file.h"

namespace relight::cli {

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

inline nlohmann::json rgbJson(const radiosity::Rgb& c) {
    return {c.r, c.g, c.b};
}

using relight::writeJsonAtomic;  // relight/io/json_file.h

}  // namespace relight::cli
