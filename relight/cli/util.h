// Small helpers shared by the subcommands: timing and JSON reports.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "radiosity/rgb.h"
#include "radiosity/stopwatch.h"
#include "relight/io/json_file.h"

namespace relight::cli {

using radiosity::Clock;
using radiosity::secondsSince;

inline nlohmann::json rgbJson(const radiosity::Rgb& c) {
    return {c.r, c.g, c.b};
}

using relight::writeJsonAtomic;  // relight/io/json_file.h

}  // namespace relight::cli
