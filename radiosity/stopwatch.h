// Seconds elapsed on the steady clock, for the phase times the solver and the dynamic
// updates report.
#pragma once

#include <chrono>

namespace radiosity {

using Clock = std::chrono::steady_clock;

/// Seconds since t0.
inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace radiosity
