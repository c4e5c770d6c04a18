// A phase given up at its deadline (runUntil, radiosity/deadline.h).
#include "radiosity/deadline.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "radiosity/parallel.h"

namespace radiosity {
namespace {

using std::chrono::milliseconds;

/// A parallel loop of `items` items of 1 ms each.
size_t slowLoop(size_t items, std::atomic<size_t>& ran) {
    parallelFor(items, 1, [&](size_t) {
        std::this_thread::sleep_for(milliseconds(1));
        ++ran;
    });
    return ran.load();
}

TEST(Deadline, ALoopThatCannotFinishIsCancelledAtTheDeadline) {
    // 4000 items of 1 ms: 2-4 s on this machine's 2 cores (a build machine may have more;
    // 64 cores would still need 62 ms). Cancelled at 50 ms, it must end long before.
    std::atomic<size_t> ran{0};
    const auto t0 = Clock::now();
    const bool whole = runUntil(t0 + milliseconds(50), [&] { slowLoop(4000, ran); });
    const double seconds = secondsSince(t0);
    EXPECT_FALSE(whole);
    EXPECT_LT(ran.load(), 4000u);
    // The chunks under way finish (1 ms each); 1 s allows for a loaded machine's scheduling.
    EXPECT_LT(seconds, 1.0);
}

TEST(Deadline, ALoopThatEndsInTimeIsWhole) {
    std::atomic<size_t> ran{0};
    const bool whole =
        runUntil(Clock::now() + std::chrono::seconds(60), [&] { slowLoop(20, ran); });
    EXPECT_TRUE(whole);
    EXPECT_EQ(ran.load(), 20u);
}

TEST(Deadline, NoDeadlineRunsToTheEnd) {
    std::atomic<size_t> ran{0};
    EXPECT_TRUE(runUntil(Clock::time_point::max(), [&] { slowLoop(20, ran); }));
    EXPECT_EQ(ran.load(), 20u);
}

TEST(Deadline, ADeadlineAlreadyPastRunsNothing) {
    bool called = false;
    EXPECT_FALSE(runUntil(Clock::now() - milliseconds(1), [&] { called = true; }));
    EXPECT_FALSE(called);
}

TEST(Deadline, AnExceptionReachesTheCaller) {
    const auto f = [] { throw std::runtime_error("phase failed"); };
    EXPECT_THROW(runUntil(Clock::now() + std::chrono::seconds(60), f), std::runtime_error);
}

}  // namespace
}  // namespace radiosity
