// Progress of a long loop, for the terminal: what a user watching a large room's
// preparation sees between one phase's name and the next.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>

#include "radiosity/stopwatch.h"

namespace radiosity {

/// Where progress messages go (a line each, no newline); empty: nowhere.
using ProgressFn = std::function<void(const std::string&)>;

/// Counts the items a loop has done, from any thread (parallelFor's workers), and reports
/// "  <what>: 45 % (135 000 of 301 101), 27 s" at most every `every` seconds: one thread
/// wins each report, the others go on without waiting.
class ProgressMeter {
  public:
    /// The solver's refinement reports as often (HierarchicalSolver::kProgressSeconds).
    static constexpr double kEverySeconds = 10;

    ProgressMeter(ProgressFn report, std::string what, size_t total, double every = kEverySeconds);

    /// `count` more items done.
    void add(size_t count);

  private:
    ProgressFn report_;
    std::string what_;
    size_t total_;
    double every_;
    Clock::time_point start_ = Clock::now();
    std::atomic<size_t> done_{0};
    std::atomic<double> next_;  ///< seconds since start_ of the next report
    std::mutex mutex_;          ///< one report at a time
};

}  // namespace radiosity
