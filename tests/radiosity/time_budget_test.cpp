// The refinement's time budget (SolverOptions::refineSeconds and refineUntil, solver.h), and
// a command's (TimeBudget, stopwatch.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "radiosity/solver.h"
#include "tests/support/cut_room.h"

using namespace radiosity;

TEST(TimeBudget, StopsTheRefinementAndKeepsTheSolutionWhole) {
    // The cut room (walls in 8 x 8 triangle pairs, a lamp on the ceiling) at a fine epsilon:
    // with no time at all the refinement stops at once. What must still hold: the flags say
    // so, fewer links are made than without the budget, the links from the lamp still reach
    // the leaves (the method needs them there, whatever the budget), and the energy stays
    // within what physics allows of a solution whose direct light is exact and whose
    // indirect light is coarse: the lamp's links deliver all of its power (normaliseLamps),
    // of which the first bounce absorbs 1 - rho = 1/2, so at least half is absorbed; the
    // energy bound lets no leaf gather more than it sees, so no more than all of it (to
    // the gather's tolerance, 1e-3). (Unrefined, the indirect light is short: 77 % is
    // absorbed against 99.99 % refined; the budget trades that for time.)
    const Scene room = test::cutRoom(8, 0.5);
    SolverOptions o;
    o.epsilon = 1e-5;
    HierarchicalSolver full(room, o);
    full.solve();
    o.refineSeconds = 1e-9;
    HierarchicalSolver cut(room, o);
    cut.solve();
    const SolverStats a = full.stats(), b = cut.stats();
    EXPECT_FALSE(a.timeBudgetReached);
    EXPECT_TRUE(b.timeBudgetReached);
    EXPECT_TRUE(b.budgetReached);
    EXPECT_LT(b.links, a.links);
    for (const Link& l : cut.links()) {
        const Node& S = cut.hierarchy().nodes[l.source];
        if (!S.isCluster() && S.emitting) {
            EXPECT_TRUE(cut.hierarchy().nodes[l.receiver].isLeaf());
        }
    }
    for (int c = 0; c < 3; ++c) {
        const double emitted = b.emittedPower[c];
        ASSERT_GT(emitted, 0);
        EXPECT_GE(b.absorbedPower[c] / emitted, 0.5) << c;
        EXPECT_LE(b.absorbedPower[c] / emitted, 1.001) << c;
        EXPECT_NEAR(a.absorbedPower[c] / emitted, 1.0, 0.01) << c;
    }
}

TEST(TimeBudget, ObjectsInsertedAfterwardsAreRefinedInFull) {
    // The budget bounds solve() only: a box inserted after a preparation that ran out of
    // time must get the links the oracle asks for, as after an unbudgeted solve. The same
    // insertion into both must make the same links for the box: its own links depend on the
    // scene's coarse links only through the radiosities they carry, so the counts agree to
    // within a few percent (measured: 504 and 506), far from the handful of links an
    // insertion makes with refinement refused.
    const Scene room = test::cutRoom(4, 0.5, /*box=*/false);
    const auto box = [] {
        std::vector<Polygon> out;
        const double lo = 0.8, hi = 1.2, z0 = 0.4, z1 = 0.8;
        const Vec3 c[8] = {{lo, lo, z0}, {hi, lo, z0}, {hi, hi, z0}, {lo, hi, z0},
                           {lo, lo, z1}, {hi, lo, z1}, {hi, hi, z1}, {lo, hi, z1}};
        const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
        for (const auto& q : f)
            out.push_back(makePolygon({c[q[0]], c[q[1]], c[q[2]], c[q[3]]}, 0, Rgb::gray(0.5)));
        return out;
    };
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver full(room, o);
    full.solve();
    o.refineSeconds = 1e-9;
    HierarchicalSolver cut(room, o);
    cut.solve();
    ASSERT_TRUE(cut.stats().timeBudgetReached);
    DynamicUpdate a, b;
    full.insertObject("box", box(), nullptr, &a);
    cut.insertObject("box", box(), nullptr, &b);
    EXPECT_GT(a.linksNew, 20);
    std::printf("links made by the insertion: %d after the full solve, %d after the budgeted one\n",
                a.linksNew, b.linksNew);
    EXPECT_NEAR(static_cast<double>(b.linksNew), static_cast<double>(a.linksNew),
                0.25 * a.linksNew);
}

TEST(TimeBudget, ItsPhasesEndAtSharesCountedFromTheStart) {
    // radiosity::TimeBudget (stopwatch.h): no budget gives "no limit" (0 seconds, the
    // largest time point), as the options it feeds read them; a share already past gives the
    // smallest positive limit, never 0 (which would read as no limit); otherwise the time
    // left is the share's seconds less what has passed, to the clock's resolution (the
    // tolerance, 1 s, is far above the microseconds between the two readings).
    const TimeBudget none{Clock::now(), 0};
    EXPECT_EQ(none.secondsUntil(0.5), 0);
    EXPECT_EQ(none.until(0.5), Clock::time_point::max());
    const TimeBudget fresh{Clock::now(), 10};
    EXPECT_NEAR(fresh.secondsUntil(0.5), 5, 1);
    EXPECT_LE(fresh.secondsUntil(0.5), 5);
    EXPECT_NEAR(std::chrono::duration<double>(fresh.until(0.65) - fresh.start).count(), 6.5, 1e-6);
    const TimeBudget spent{Clock::now() - std::chrono::seconds(100), 10};
    EXPECT_EQ(spent.secondsUntil(0.5), TimeBudget::kSpentSeconds);
    EXPECT_LT(spent.until(1.0), Clock::now());
}

TEST(TimeBudget, APhaseThatMustNotBeCutKeepsItsOwnShareWhenTheOnesBeforeOverran) {
    // TimeBudget::secondsUntilAtLeast (the reflectance rounds): on time, the seconds until its
    // cumulative end; past it, its own share of the budget, not the smallest limit; without a
    // budget, no limit (0). Tolerance 1 s as above.
    const TimeBudget fresh{Clock::now(), 10};
    EXPECT_NEAR(fresh.secondsUntilAtLeast(0.65, 0.15), 6.5, 1);
    const TimeBudget spent{Clock::now() - std::chrono::seconds(100), 10};
    EXPECT_DOUBLE_EQ(spent.secondsUntilAtLeast(0.65, 0.15), 1.5);
    const TimeBudget none{Clock::now(), 0};
    EXPECT_EQ(none.secondsUntilAtLeast(0.65, 0.15), 0);
}

TEST(TimeBudget, APhaseBegunEarlyEndsAfterItsOwnShare) {
    // TimeBudget::phaseUntil: begun before the earlier shares have passed, a phase ends after
    // its own share; begun late, at its cumulative end; without a budget, never. Durations
    // are exact here (no clock reading but the start's): 1e-6 s is the double's rounding.
    const auto t0 = Clock::now();
    const TimeBudget b{t0, 100};
    auto at = [&](Clock::time_point t) { return std::chrono::duration<double>(t - t0).count(); };
    EXPECT_NEAR(at(b.phaseUntil(t0 + std::chrono::seconds(30), 0.10, 0.75)), 40, 1e-6);
    EXPECT_NEAR(at(b.phaseUntil(t0 + std::chrono::seconds(70), 0.10, 0.75)), 75, 1e-6);
    EXPECT_NEAR(at(b.phaseUntil(t0 + std::chrono::seconds(90), 0.10, 0.75)), 75, 1e-6);
    const TimeBudget none{t0, 0};
    EXPECT_EQ(none.phaseUntil(t0, 0.10, 0.75), Clock::time_point::max());
}

TEST(TimeBudget, AHugeBudgetIsNoDeadlineNotOnePast) {
    // radiosity::secondsAfter saturates: 1e300 s (or 1e12 s, past the clock's ~292 years of
    // nanoseconds) is no deadline, where the integer ticks overflowed into the past and
    // every phase read as spent; a small duration is exact to the nanosecond; not finite
    // is no deadline, negative is now.
    const auto t0 = Clock::now();
    EXPECT_EQ(secondsAfter(t0, 1e300), Clock::time_point::max());
    EXPECT_EQ(secondsAfter(t0, 1e12), Clock::time_point::max());
    EXPECT_EQ(secondsAfter(t0, std::numeric_limits<double>::infinity()), Clock::time_point::max());
    EXPECT_EQ(secondsAfter(t0, std::nan("")), Clock::time_point::max());
    EXPECT_EQ(secondsAfter(t0, -5), t0);
    EXPECT_EQ(secondsAfter(t0, 1.5) - t0, std::chrono::milliseconds(1500));
    const TimeBudget huge{t0, 1e300};
    EXPECT_EQ(huge.until(0.5), Clock::time_point::max());
    EXPECT_EQ(huge.phaseUntil(t0, 0.1, 0.75), Clock::time_point::max());
    EXPECT_GT(huge.secondsUntil(0.5), 1e299);
}

TEST(TimeBudget, ADeadlineAlreadyPastStopsTheRefinementAsNoTimeDoes) {
    // SolverOptions::refineUntil, a command's budget counted from its start: when the loading
    // took all of the refinement's share, the refinement stops at its first reading of the
    // clock, exactly as with no time at all (refineSeconds 1e-9): the same links.
    const Scene room = test::cutRoom(8, 0.5);
    SolverOptions o;
    o.epsilon = 1e-5;
    o.refineSeconds = 1e-9;
    HierarchicalSolver a(room, o);
    a.solve();
    o.refineSeconds = 0;
    o.refineUntil = Clock::now() - std::chrono::seconds(1);
    HierarchicalSolver b(room, o);
    b.solve();
    EXPECT_TRUE(b.stats().timeBudgetReached);
    EXPECT_EQ(a.stats().links, b.stats().links);
    EXPECT_EQ(a.stats().leaves, b.stats().leaves);
}

TEST(TimeBudget, OnceTheRefinementIsOverASolveRefinesNothing) {
    // HierarchicalSolver::refinementOver(): past SolverOptions::refineUntil a solve() would
    // refine no link (the reflectance estimate skips its closing solve then). Without a
    // deadline the refinement is never over.
    const Scene room = test::cutRoom(8, 0.5);
    SolverOptions o;
    o.epsilon = 1e-5;
    o.refineUntil = Clock::now() - std::chrono::seconds(1);
    HierarchicalSolver late(room, o);
    late.solve();
    ASSERT_TRUE(late.refinementOver());
    const SolverStats before = late.stats();
    late.solve();
    EXPECT_EQ(late.stats().links, before.links);
    EXPECT_EQ(late.stats().leaves, before.leaves);
    o.refineUntil = Clock::time_point::max();
    HierarchicalSolver free(room, o);
    free.solve();
    EXPECT_FALSE(free.refinementOver());
}

TEST(TimeBudget, PastTheDeadlineWhatLeavesSeeIsNotMeasuredAndTheyStayUnbounded) {
    // What the leaves see (the energy bound's measurement) is measured before the
    // refinement, given up at its deadline: with the deadline already past, no reflecting
    // leaf is measured and the bound leaves every one of them as it is (gatherScale 1), and
    // no second round begins. Without a deadline every leaf is measured.
    const Scene room = test::cutRoom(4, 0.5);
    SolverOptions o;
    o.refineUntil = Clock::now() - std::chrono::seconds(1);
    HierarchicalSolver late(room, o);
    late.solve();
    EXPECT_EQ(late.stats().refineRounds, 1);
    o.refineUntil = Clock::time_point::max();
    HierarchicalSolver whole(room, o);
    whole.solve();
    int leaves = 0;
    for (const Node& n : late.hierarchy().nodes) {
        if (n.isCluster() || !n.isLeaf() || n.emitting) continue;
        ++leaves;
        EXPECT_LT(n.seen, 0);
        EXPECT_EQ(n.gatherScale, 1.0);
    }
    EXPECT_GT(leaves, 0);
    for (const Node& n : whole.hierarchy().nodes)
        if (!n.isCluster() && n.isLeaf()) {
            EXPECT_GE(n.seen, 0);
        }
}
