// A phase that may be given up at a deadline: its parallel loops (parallelFor, TBB's
// algorithms) are cancelled when the deadline passes, so that a command's --time-budget
// holds even where a phase's cost cannot be told in advance (a final gather whose cost is
// set by the links above its points, not by their number).
#pragma once

#include <tbb/task_group.h>

#include <condition_variable>
#include <mutex>
#include <thread>

#include "radiosity/stopwatch.h"

namespace radiosity {

/// Runs f() on TBB's threads; when `deadline` passes before f() returns, the parallel
/// loops that f() runs are cancelled: their chunks not yet begun are skipped, f()'s serial
/// code runs on to its end. Returns true when f() ran to its end uncancelled (then its
/// results are whole); false when it was cancelled (then its results are partial and must
/// be thrown away). An exception from f() is rethrown.
template <class F>
bool runUntil(Clock::time_point deadline, F&& f) {
    if (deadline == Clock::time_point::max()) {
        f();
        return true;
    }
    if (Clock::now() >= deadline) return false;
    tbb::task_group group;
    std::mutex m;
    std::condition_variable cv;
    bool done = false, cancelled = false;
    // The watchdog sleeps until the deadline or until f() is done, whichever comes first.
    std::thread watchdog([&] {
        std::unique_lock<std::mutex> lock(m);
        if (cv.wait_until(lock, deadline, [&] { return done; })) return;
        cancelled = true;
        group.cancel();
    });
    const auto stopWatchdog = [&] {
        {
            std::lock_guard<std::mutex> lock(m);
            done = true;
        }
        cv.notify_one();
        watchdog.join();
    };
    try {
        group.run([&] { f(); });
        group.wait();
    } catch (...) {
        stopWatchdog();
        throw;
    }
    stopWatchdog();
    // Cancelled as f() ended, whole results are given up too: the deadline had passed.
    return !cancelled;
}

}  // namespace radiosity
