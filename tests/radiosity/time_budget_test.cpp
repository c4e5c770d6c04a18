// The refinement's time budget (SolverOptions::refineSeconds, solver.h).
#include <gtest/gtest.h>

#include <cmath>

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
