// Small helpers the benchmark programs share.
#pragma once

#include <chrono>

namespace bench {

using Clock = std::chrono::steady_clock;

/// Seconds since t0.
inline double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace bench
