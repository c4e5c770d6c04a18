// LightResponses and finalGatherResponses: the solution split by light equals the solution
// of the same links re-gathered with the lights' new radiances (linearity in emittance).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "radiosity/final_gather.h"
#include "radiosity/light_response.h"
#include "radiosity/solver.h"

using namespace radiosity;

namespace {

/// A 4 m x 4 m floor with a plate above half of it (both grey 0.5) and two lamps facing
/// down at different places: light 1 starts switched off when `secondOn` is false.
Scene twoLamps(bool secondOn) {
    Scene s;
    s.objects = {"floor", "plate", "lamps"};
    s.polygons.push_back(
        makePolygon({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(makePolygon({{-2, -2, 0.5}, {-2, 2, 0.5}, {0, 2, 0.5}, {0, -2, 0.5}}, 1,
                                     Rgb{0.7, 0.5, 0.3}));
    auto lamp = [&](double cx, const Rgb& L, const char* name) {
        Polygon p = makePolygon(
            {{cx - 0.3, -0.3, 1}, {cx - 0.3, 0.3, 1}, {cx + 0.3, 0.3, 1}, {cx + 0.3, -0.3, 1}}, 2,
            Rgb{});
        p.light = static_cast<int>(s.lights.size());
        s.lights.push_back({name, {static_cast<int>(s.polygons.size())}, L});
        s.polygons.push_back(p);
    };
    lamp(-0.5, Rgb::gray(3.0), "left");
    lamp(1.0, secondOn ? Rgb{1, 2, 0.5} : Rgb{}, "right");
    return s;
}

SolverOptions tightOptions() {
    SolverOptions o;
    o.epsilon = 1e-3;
    // Both paths iterate to the same fixed point; a tolerance far below the assertion's
    // 1e-6 keeps the convergence error out of the comparison. (The tolerance bounds the
    // change of the total power; with the energy bound's per-leaf scales, light still moves
    // between regions when the total has settled: 1e-10 left 9e-6 at a dim point.)
    o.tolerance = 1e-14;
    return o;
}

/// Largest |a - b| over the leaves, relative to the largest B.
double leafDifference(const HierarchicalSolver& solver, const std::vector<Rgb>& expected) {
    const auto& nodes = solver.hierarchy().nodes;
    double maxB = 0, maxDiff = 0;
    for (size_t n = 0; n < nodes.size(); ++n) {
        if (nodes[n].isCluster() || !nodes[n].isLeaf()) continue;
        maxB = std::max(maxB, nodes[n].B.maxComponent());
        for (int c = 0; c < 3; ++c)
            maxDiff = std::max(maxDiff, std::abs(nodes[n].B[c] - expected[n][c]));
    }
    return maxB > 0 ? maxDiff / maxB : maxDiff;
}

void checkSuperposition(bool secondOn, double refineSeconds = 0) {
    SolverOptions o = tightOptions();
    o.refineSeconds = refineSeconds;
    HierarchicalSolver solver(twoLamps(secondOn), o);
    solver.solve();
    EXPECT_EQ(solver.stats().timeBudgetReached, refineSeconds > 0);
    const LightResponses responses(solver);
    const std::vector<Rgb> radiance = {{0.4, 2.0, 1.1}, {2.5, 0.2, 1.0}};
    // Superposition: B = E + sum_l L_l R_l, with E from the new radiances.
    solver.setLightRadiances(radiance);
    const auto& nodes = solver.hierarchy().nodes;
    std::vector<Rgb> sum(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n)
        sum[n] = nodes[n].E + responses.reflected(static_cast<int>(n), radiance);
    // The re-gather path has just run (setLightRadiances): compare.
    EXPECT_LT(leafDifference(solver, sum), 1e-6);
}

}  // namespace

TEST(LightResponses, WeightedSumEqualsReGather) {
    checkSuperposition(true);
}

TEST(LightResponses, WeightedSumEqualsReGatherOnCoarseLinks) {
    // The split by light holds on whatever links the time budget left (here: none refined
    // below the first round): switching a lamp off removes exactly its share, because the
    // shares and the solution are gathered through the same links (linearity, same 1e-6).
    // Whatever error coarse links make is in the solution itself, not in its split.
    checkSuperposition(true, 1e-9);
    checkSuperposition(false, 1e-9);
}

TEST(LightResponses, LightOffWhenSolvedGetsLinksAndAResponse) {
    // The right lamp had no links when the solution was refined; its response must be
    // complete all the same, so switching it on by superposition matches a re-gather.
    checkSuperposition(false);
    HierarchicalSolver solver(twoLamps(false), tightOptions());
    solver.solve();
    const LightResponses responses(solver);
    double right = 0;
    for (size_t n = 0; n < solver.hierarchy().nodes.size(); ++n)
        right = std::max(right, responses.reflected(static_cast<int>(n))[1].maxComponent());
    EXPECT_GT(right, 0.0);
    // The solver's own state is restored: the right lamp is still off.
    EXPECT_EQ(solver.scene().lights[1].radiance, Rgb{});
}

TEST(LightResponses, GatheredResponsesSumToTheFinalGather) {
    // Same links, same rays (same seed), per-light sources: sum_l L_l H_l(x) equals the
    // final gather of the re-gathered solution up to the solution's convergence.
    HierarchicalSolver solver(twoLamps(true), tightOptions());
    solver.solve();
    const LightResponses responses(solver);
    const std::vector<Rgb> radiance = {{1.0, 0.2, 0.7}, {0.1, 1.5, 2.0}};
    solver.setLightRadiances(radiance);
    for (const Vec3 x : {Vec3{0.5, 0.3, 0}, Vec3{-1.0, 1.2, 0}, Vec3{1.9, -1.9, 0}}) {
        Rgb H[2];
        finalGatherResponses(solver, responses, 0, x, H, 4, 11);
        const Rgb sum = radiance[0] * H[0] + radiance[1] * H[1];
        const Rgb direct = finalGatherIndirect(solver, 0, x, 4, 11);
        ASSERT_GT(direct.maxComponent(), 0.0);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], direct[c], 1e-6 * direct.maxComponent());
    }
}

TEST(LightResponses, LeaveTheSolverSolutionAsItWas) {
    // The responses are solved on arrays of their own: every node's B is bit for bit what
    // the solve left.
    HierarchicalSolver solver(twoLamps(true), tightOptions());
    solver.solve();
    std::vector<Rgb> before;
    for (const Node& n : solver.hierarchy().nodes) before.push_back(n.B);
    const LightResponses responses(solver);
    ASSERT_EQ(before.size(), solver.hierarchy().nodes.size());
    for (size_t n = 0; n < before.size(); ++n)
        ASSERT_EQ(solver.hierarchy().nodes[n].B, before[n]) << n;
}

TEST(LightResponses, WarmStartReachesTheSameResponsesInFewerSweeps) {
    // After a reflectance change, starting from the old responses must give the responses
    // of a cold start (the same fixed point, to well within the 1e-6 of the superposition
    // tests), in fewer sweeps.
    HierarchicalSolver solver(twoLamps(true), tightOptions());
    solver.solve();
    auto old = std::make_unique<LightResponses>(solver);
    solver.setReflectance(0, Rgb{0.45, 0.5, 0.55});
    solver.pullReflectance();
    const LightResponses cold(solver), warm(solver, std::move(old));
    double maxR = 0, maxDiff = 0;
    for (size_t n = 0; n < solver.hierarchy().nodes.size(); ++n)
        for (int l = 0; l < 2; ++l) {
            const Rgb a = cold.reflected(static_cast<int>(n))[l];
            const Rgb b = warm.reflected(static_cast<int>(n))[l];
            maxR = std::max(maxR, a.maxComponent());
            for (int c = 0; c < 3; ++c) maxDiff = std::max(maxDiff, std::abs(a[c] - b[c]));
        }
    ASSERT_GT(maxR, 0.0);
    EXPECT_LT(maxDiff / maxR, 1e-9);
    EXPECT_LT(warm.sweeps(), cold.sweeps());
}
