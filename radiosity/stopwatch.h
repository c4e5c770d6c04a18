// Seconds elapsed on the steady clock: the one clock of every time the project reports
// (the solver's phases, the dynamic updates, the relighting's steps, the commands'
// reports, the viewer's frames, the bench programs).
#pragma once

#include <chrono>

namespace radiosity {

using Clock = std::chrono::steady_clock;

/// Seconds since t0.
inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace radiosity
