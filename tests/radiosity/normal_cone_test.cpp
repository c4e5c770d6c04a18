// Normal cones of clusters and the normal-cone bound on the form factor (transfer.h).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/rng.h"
#include "radiosity/detail/transfer.h"
#include "radiosity/hierarchy.h"
#include "radiosity/visibility.h"
#include "tests/support/grids.h"

using namespace radiosity;

namespace {

/// A 1 x 1 m floor cut into an n x n grid of triangle pairs whose inner vertices are
/// raised by up to `bump` metres: a reconstruction's rough floor.
Scene bumpyFloor(int n, double bump, uint64_t seed) {
    Rng rng(seed);
    std::vector<double> z((n + 1) * (n + 1), 0.0);
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) z[j * (n + 1) + i] = bump * (2 * rng.uniform() - 1);
    auto at = [&](int i, int j) {
        return Vec3{static_cast<double>(i) / n, static_cast<double>(j) / n, z[j * (n + 1) + i]};
    };
    Scene s;
    s.objects = {"floor"};
    test::addTriangleGrid(s, n, at, 0, Rgb::gray(0.5));
    return s;
}

/// F_{R -> S} between two nodes by their polygons: the area-weighted mean over R's
/// polygons of the sum over S's of the exact polygon-to-polygon form factor (order-6
/// quadrature on the receiver; unoccluded, as the bound is).
double formFactorByPolygons(const Hierarchy& h, const Scene& s, int r, int t) {
    const Node& R = h.nodes[r];
    const Node& S = h.nodes[t];
    double sum = 0;
    for (int i = R.polyBegin; i < R.polyEnd; ++i) {
        const Polygon& a = s.polygons[h.polygonOrder[i]];
        double f = 0;
        for (int k = S.polyBegin; k < S.polyEnd; ++k) {
            const Polygon& b = s.polygons[h.polygonOrder[k]];
            f += polygonToPolygon(a.v.data(), a.vertexCount, a.normal, b.v.data(), b.vertexCount,
                                  b.normal, 6);
        }
        sum += a.area * f;
    }
    return sum / R.area;
}

}  // namespace

TEST(NormalCone, HoldsEveryPolygonNormalOfTheCluster) {
    const Scene s = bumpyFloor(8, 0.01, 3);
    const Hierarchy h(s);
    int clusters = 0;
    for (const Node& c : h.nodes) {
        if (!c.isCluster()) continue;
        ++clusters;
        EXPECT_NEAR(glm::length(h.coneAxis(c)), 1.0, 1e-12);
        for (int i = c.polyBegin; i < c.polyEnd; ++i) {
            const double a = std::acos(std::clamp(
                glm::dot(h.coneAxis(c), s.polygons[h.polygonOrder[i]].normal), -1.0, 1.0));
            EXPECT_LE(a, h.coneAngle(c) + 1e-12);
        }
    }
    EXPECT_GT(clusters, 16);
}

TEST(NormalCone, BoundsTheExchangeOfTouchingPatchesOfARoughFloor) {
    // Two neighbouring patches of a rough floor (the root's children, and every pair of
    // sibling clusters below): their bounding spheres overlap, so the distance bound says
    // 1. The cone bound 8 delta^2 must hold against the exact unoccluded form factor
    // summed over their triangles (it is a bound: no tolerance but the quadrature's,
    // 1e-9), in both directions, and so must the links' estimates. With bumps of 3 mm on
    // 12.5 cm cells (slopes of a few degrees) it is far below 1.
    const Scene s = bumpyFloor(8, 0.003, 7);
    const Hierarchy h(s);
    const Visibility vis(s);
    const TransferEvaluator transfer(h, vis, {});
    int pairs = 0;
    double largestExact = 0;
    for (size_t c = 0; c < h.nodes.size(); ++c) {
        const Node& P = h.nodes[c];
        if (!P.isCluster() || P.childCount != 2 || !h.nodes[P.firstChild].isCluster()) continue;
        const int a = P.firstChild, b = P.firstChild + 1;
        const double cone = transfer.coneBound(a, b);
        EXPECT_DOUBLE_EQ(cone, transfer.coneBound(b, a));
        EXPECT_LT(cone, 0.1) << c;
        for (auto [r, t] : {std::pair{a, b}, std::pair{b, a}}) {
            const double exact = formFactorByPolygons(h, s, r, t);
            largestExact = std::max(largestExact, exact);
            EXPECT_LE(exact, cone + 1e-9) << c;
            EXPECT_LE(transfer.formFactor(r, t), cone) << c;
            EXPECT_LE(transfer.bound(r, t, transfer.formFactor(r, t)), cone) << c;
        }
        ++pairs;
    }
    EXPECT_GT(pairs, 4);
    EXPECT_GT(largestExact, 0.0);  // rough: the patches do exchange a little
}

TEST(NormalCone, NoBoundForSurfacesThatFaceEachOther) {
    // A floor and a ceiling facing it: normals opposite, no band, no bound.
    Scene s;
    s.objects = {"floor", "ceiling"};
    s.polygons.push_back(
        makePolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(
        makePolygon({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, 1, Rgb::gray(0.5)));
    const Hierarchy h(s, 1);
    const Visibility vis(s);
    const TransferEvaluator transfer(h, vis, {});
    const int a = h.polygonRoot[0], b = h.polygonRoot[1];
    EXPECT_EQ(transfer.coneBound(a, b), 1.0);
}

TEST(SelfTransfer, BoundsTheAnalyticSelfExchangeOfAGrooveAndATrough) {
    // Two closed forms in 2D (infinitely long surfaces; Hottel's crossed strings):
    // - a V-groove of two equal strips at opening angle a: each sends 1 - sin(a/2) of its
    //   light to the other; its normals lie within t = (pi - a)/2 of the bisector;
    // - a concave circular arc of half-angle t: it sends 1 - sin(t)/t of its light to
    //   itself (its chord takes the rest); its normals lie within t of the axis.
    // The bound must hold for every t, be 0 for a plane and not be vacuous for a nearly
    // flat surface (the solver defers self-interactions on it): below 0.04 at 5 degrees.
    const double pi = std::numbers::pi;
    for (double deg = 0.5; deg < 90; deg += 0.5) {
        const double t = deg * pi / 180;
        const double bound = selfTransferBound(t);
        EXPECT_GE(bound, 1 - std::sin((pi - 2 * t) / 2)) << deg;  // the groove
        EXPECT_GE(bound, 1 - std::sin(t) / t) << deg;             // the trough
        EXPECT_LE(bound, 1.0);
    }
    EXPECT_EQ(selfTransferBound(0), 0.0);
    EXPECT_LT(selfTransferBound(5 * pi / 180), 0.04);
    EXPECT_EQ(selfTransferBound(pi), 1.0);  // a cluster without a cone
    EXPECT_EQ(selfTransferBound(std::nan("")), 1.0);
}
