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

/// The time point `seconds` after t, saturated at the clock's last: the clock counts
/// integer nanoseconds, and `--time-budget 1e300` overflowed them into the past, where every
/// phase read as spent (a silently coarse preparation). Not finite, or past half of what
/// the clock can still count (about 146 years), gives the last time point ("no deadline");
/// not positive gives t.
inline Clock::time_point secondsAfter(Clock::time_point t, double seconds) {
    const double room = std::chrono::duration<double>(Clock::time_point::max() - t).count();
    if (!(seconds < 0.5 * room)) return Clock::time_point::max();
    if (!(seconds > 0)) return t;
    return t + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
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
    /// Seconds a phase has until `ends` (cumulative) of the budget has passed, but at least
    /// its own `share` of the budget, for a phase that must not be cut below it when the
    /// phases before it overran theirs (0 without a budget).
    double secondsUntilAtLeast(double ends, double share) const {
        if (!(seconds > 0)) return 0;
        return std::max(secondsUntil(ends), seconds * share);
    }
    /// The time point at which `share` of the budget has passed; the largest time point
    /// without a budget.
    Clock::time_point until(double share) const {
        if (!(seconds > 0)) return Clock::time_point::max();
        return secondsAfter(start, seconds * share);
    }
    /// The end of a phase begun at `begun` that may take `share` of the budget and must
    /// end when the cumulative share `ends` has passed: the sooner of the two. A phase with
    /// a fallback that begins early (the phases before it left time) then leaves that time
    /// to the phases after it, whose costs have no fallback. The largest time point
    /// without a budget.
    Clock::time_point phaseUntil(Clock::time_point begun, double share, double ends) const {
        if (!(seconds > 0)) return Clock::time_point::max();
        return std::min(until(ends), secondsAfter(begun, seconds * share));
    }
    static constexpr double kSpentSeconds = 1e-3;
};

}  // namespace radiosity
