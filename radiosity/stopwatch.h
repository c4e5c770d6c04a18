// Seconds elapsed on the steady clock: the one clock of every time the project reports
// (the solver's phases, the dynamic updates, the relighting's steps, the commands'
// reports, the viewer's frames, the bench programs).
#pragma once

#include <algorithm>
#include <chrono>

namespace radiosity {

using Clock = std::chrono::steady_clock;

/// Seconds since t0.
inline double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// A command's wall-clock budget (--time-budget), counted from its start: each phase ends
/// when a share of the whole has passed since then, so that a phase that overran (or the
/// loading of a large mesh) shortens the phases after it instead of lengthening the command.
struct TimeBudget {
    Clock::time_point start = Clock::now();
    double seconds = 0;  ///< 0: no budget

    /// Seconds a phase has until `share` (cumulative, in [0, 1]) of the budget has passed:
    /// 0 without a budget (the "no limit" of the options it feeds), and at least
    /// kSpentSeconds once that time is past (a limit that is already reached).
    double secondsUntil(double share) const {
        if (!(seconds > 0)) return 0;
        return std::max(kSpentSeconds, seconds * share - secondsSince(start));
    }
    /// The time point at which `share` of the budget has passed; the largest time point
    /// without a budget.
    Clock::time_point until(double share) const {
        if (!(seconds > 0)) return Clock::time_point::max();
        return start + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(seconds * share));
    }
    static constexpr double kSpentSeconds = 1e-3;
};

}  // namespace radiosity
