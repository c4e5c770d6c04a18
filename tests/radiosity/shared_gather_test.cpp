// sharedFinalGather: the final gather of many points with the far links gathered once per
// corner of their receiving element and interpolated, against the same gather per point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "furnace.h"
#include "radiosity/final_gather.h"
#include "radiosity/light_response.h"
#include "radiosity/shared_gather.h"
#include "radiosity/solver.h"
#include "tests/support/cut_room.h"

using namespace radiosity;

namespace {

/// A long hall, 12 x 3 x 3 m (faces inward, reflectance 0.6), lit by a 0.5 m lamp under
/// the ceiling near one end: the far end's floor gathers from sources many times farther
/// than its elements are large (far links), the lamp's end from near ones.
Scene hall() {
    Scene s;
    s.objects = {"hall", "lamp"};
    for (const auto& f : test::boxFacesInward(12, 3, 3))
        s.polygons.push_back(makePolygon(f, 0, Rgb{0.6, 0.5, 0.4}));
    Polygon lamp =
        makePolygon({{1, 1.25, 2.9}, {1, 1.75, 2.9}, {1.5, 1.75, 2.9}, {1.5, 1.25, 2.9}}, 1, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(20.0)});
    s.polygons.push_back(lamp);
    return s;
}

/// The hall with a 0.4 m block on the floor under its lamp (x 1.0-1.4 m), each face cut into
/// 4 x 4 triangle pairs, as furniture comes.
Scene hallWithCutBlock() {
    Scene s = hall();
    s.objects.push_back("block");
    const double x0 = 1.0, x1 = 1.4, y0 = 1.3, y1 = 1.7, z1 = 0.4;
    const Vec3 c[8] = {{x0, y0, 0},  {x1, y0, 0},  {x1, y1, 0},  {x0, y1, 0},
                       {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
    const int f[5][4] = {{4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (const auto& q : f)
        test::addCutQuad(s, {c[q[0]], c[q[1]], c[q[2]], c[q[3]]}, 4, 2, Rgb::gray(0.7));
    return s;
}

/// The shared gather against the per-point one (red channel): the largest relative
/// difference at a point, and the sums of both over the points (each point's must be > 0).
std::tuple<double, double, double> againstPerPoint(const HierarchicalSolver& solver,
                                                   const SharedGather& g,
                                                   const std::vector<GatherPoint>& points) {
    std::vector<Rgb> shared(points.size());
    g.addIndirect(solver, shared.data());
    double sumShared = 0, sumPoint = 0, worst = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        const Rgb H =
            finalGatherIndirect(solver, points[i].polygon, points[i].x, 4, points[i].seed);
        EXPECT_GT(H.r, 0.0);
        worst = std::max(worst, std::abs(shared[i].r - H.r) / std::max(H.r, 1e-300));
        sumShared += shared[i].r;
        sumPoint += H.r;
    }
    return {worst, sumShared, sumPoint};
}

}  // namespace

TEST(SharedGather, MatchesThePerPointGatherWhereLinksAreFar) {
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver solver(hall(), o);
    solver.solve();
    // Points over the floor (polygon 0) and the far end wall (polygon 5, x = 12).
    std::vector<GatherPoint> points;
    for (int i = 0; i < 24; ++i)
        for (int j = 0; j < 6; ++j)
            points.push_back({0, Vec3{0.25 + 0.5 * i, 0.25 + 0.5 * j, 0}, uint64_t(i * 6 + j)});
    for (int j = 0; j < 6; ++j)
        for (int k = 0; k < 6; ++k)
            points.push_back({5, Vec3{12, 0.25 + 0.5 * j, 0.25 + 0.5 * k}, uint64_t(500 + j)});
    const SharedGather g = sharedFinalGather(solver, points, 4);
    ASSERT_EQ(g.points(), points.size());
    // The hall has far links, and the floor's elements are met by several points each.
    EXPECT_GT(g.sharedLinks, 0u);
    // An empty room: no PARTIAL link, so no ray, and both are deterministic.
    const auto [worst, sumShared, sumPoint] = againstPerPoint(solver, g, points);
    // A far link's transfer misses its affine fit by at most about 3 (R_r / d)^2 / 4 < 5 %
    // of itself at kFar = 4 (shared_gather.h); far links are a part of each point's light,
    // so each point is within 5 % and the sum within 1 % (errors of both signs over an
    // element: the fit is a least-squares one).
    EXPECT_LT(worst, 0.05);
    EXPECT_NEAR(sumShared / sumPoint, 1.0, 0.01);
}

TEST(SharedGather, ResponsesSumToTheIndirectGather) {
    // Per unit radiance of the one lamp, times its radiance, the responses' gather is the
    // radiosities' gather: the same terms, weighed by R_l instead of B.
    SolverOptions o;
    o.epsilon = 1e-3;
    // Both iterate to the same fixed point; a tolerance far below the assertion's keeps the
    // convergence error out of the comparison (as LightResponses' own test does).
    o.tolerance = 1e-14;
    HierarchicalSolver solver(hall(), o);
    solver.solve();
    const LightResponses responses(solver);
    std::vector<GatherPoint> points;
    for (int i = 0; i < 12; ++i) points.push_back({0, Vec3{0.5 + i, 1.5, 0}, uint64_t(i)});
    points.push_back({-1, Vec3{}, 0});  // no gather: left at zero
    const SharedGather g = sharedFinalGather(solver, points, 4);
    std::vector<Rgb> byB(points.size()), byR(points.size());
    g.addIndirect(solver, byB.data());
    g.addResponses(responses, byR.data());
    for (size_t i = 0; i + 1 < points.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(byR[i][c] * 20.0, byB[i][c], 1e-6 * byB[i].maxComponent()) << i << " " << c;
    EXPECT_EQ(byB.back().r, 0.0);
    EXPECT_EQ(byR.back().r, 0.0);
}

TEST(SharedGather, PastItsTimeItKeepsThePartialLinksMeanVisibility) {
    // The hall with a two-sided panel under the lamp: the floor's links to the lamp and to
    // the ceiling above the panel are PARTIAL, so the gather casts rays.
    Scene s = hall();
    const std::vector<Vec3> up = {{0.5, 0.5, 1.5}, {3, 0.5, 1.5}, {3, 2.5, 1.5}, {0.5, 2.5, 1.5}};
    s.polygons.push_back(makePolygon(up, 0, Rgb::gray(0.5)));
    s.polygons.push_back(makePolygon({up[3], up[2], up[1], up[0]}, 0, Rgb::gray(0.5)));
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver solver(s, o);
    solver.solve();
    std::vector<GatherPoint> points;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 6; ++j)
            points.push_back({0, Vec3{0.25 + 0.5 * i, 0.25 + 0.5 * j, 0}, uint64_t(i * 6 + j)});
    const SharedGather full = sharedFinalGather(solver, points, 4);
    EXPECT_GT(full.rays, 0u);  // the fallback below changes something
    EXPECT_EQ(full.withoutRays, 0u);
    // A deadline already passed: no ray at any corner or point, every one counted, and the
    // terms exactly those of a gather that never casts rays (partialRays 0).
    const SharedGather late = sharedFinalGather(solver, points, 4, {}, Clock::time_point::min());
    const SharedGather none = sharedFinalGather(solver, points, 0);
    EXPECT_EQ(late.rays, 0u);
    EXPECT_EQ(late.withoutRays, late.samples() + late.points());
    const auto same = [](const BlockedLists<GatherWeight>& a, const BlockedLists<GatherWeight>& b) {
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
            ASSERT_EQ(a[i].size(), b[i].size());
            for (size_t t = 0; t < a[i].size(); ++t) {
                EXPECT_EQ(a[i][t].node, b[i][t].node);
                EXPECT_EQ(a[i][t].w, b[i][t].w);
            }
        }
    };
    same(late.pointTerms, none.pointTerms);
    same(late.sampleTerms, none.sampleTerms);
    EXPECT_GT(late.terms(), 0u);
}

TEST(SharedGather, ALeafOfManyPointsGathersItsAncestorsNearLinksAtItsCorners) {
    // The hall with a lit block cut into small triangles, met by a dense grid of points (16
    // per square metre of floor: several per leaf): the floor's elements hold links to the
    // block's triangles one by one, near the floor element as a whole yet far from each of
    // its leaves away from the block, which a leaf of more than 8 points gathers at its
    // corners (sharedFinalGather). The bound is that of
    // MatchesThePerPointGatherWhereLinksAreFar, since the fit over a leaf is the fit over an
    // element: each point within 5 % of its own gather, the sum within 1 %. At epsilon 1e-3:
    // the oracle splits a floor element before it opens the block's small face clusters
    // (kElementFirstRatio), so that at 1e-2 the links from the block stay on few large
    // pieces and hardly any reach a leaf's ancestor one triangle at a time (18 did).
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver solver(hallWithCutBlock(), o);
    solver.solve();
    std::vector<GatherPoint> points;
    for (int i = 0; i < 48; ++i)
        for (int j = 0; j < 12; ++j)
            points.push_back(
                {0, Vec3{0.125 + 0.25 * i, 0.125 + 0.25 * j, 0}, uint64_t(i * 12 + j)});
    const SharedGather g = sharedFinalGather(solver, points, 4);
    EXPECT_GT(g.leafSharedLinks, 0u);
    const auto [worst, sumShared, sumPoint] = againstPerPoint(solver, g, points);
    // What the block sends the floor, alone: its share of the gather is what the leaves'
    // corners carry (the rest is as in the per-point gather).
    const auto& nodes = solver.hierarchy().nodes;
    std::vector<Rgb> blockOnly(nodes.size());
    for (size_t n = 0; n < nodes.size(); ++n)
        if (!nodes[n].isCluster() && nodes[n].polygon >= 7) blockOnly[n] = nodes[n].B;
    double sumBlock = 0;
    for (const GatherPoint& p : points)
        sumBlock += finalGatherField(solver, blockOnly, p.polygon, p.x, 4, p.seed).r;
    std::printf("leaf-shared links %zu, worst %.5f, sum ratio %.6f, the block's share %.4f\n",
                g.leafSharedLinks, worst, sumShared / sumPoint, sumBlock / sumPoint);
    EXPECT_LT(worst, 0.05);
    EXPECT_NEAR(sumShared / sumPoint, 1.0, 0.01);
    // A link counted twice (at the leaf's corners and at the point) or not at all would move
    // the sum by up to the block's share; the fit moves it by at most 5 % of that share.
    EXPECT_GT(sumBlock / sumPoint, 1e-3);
    EXPECT_LT(std::abs(sumShared / sumPoint - 1), 0.05 * sumBlock / sumPoint);
}
