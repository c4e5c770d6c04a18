// Support for texture-based refinement (Loscos et al. 2000, §4.2): splitting a leaf moves
// its light links to the children, unsplitting restores the solution exactly; leaf
// neighbours across edges.
#include <gtest/gtest.h>

#include <algorithm>

#include "radiosity/detail/form_factor.h"
#include "radiosity/hierarchy.h"
#include "radiosity/solver.h"

using namespace radiosity;

namespace {

/// A 4 m x 4 m grey floor, a plate 0.5 m above its left half and a lamp above the plate's
/// edge facing down: the floor holds umbra, penumbra and lit leaves.
Scene plateShadow() {
    Scene s;
    s.objects = {"floor", "plate", "lamp"};
    s.polygons.push_back(
        makePolygon({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(
        makePolygon({{-2, -2, 0.5}, {-2, 2, 0.5}, {0, 2, 0.5}, {0, -2, 0.5}}, 1, Rgb::gray(0.5)));
    Polygon p =
        makePolygon({{-0.3, -0.3, 1}, {-0.3, 0.3, 1}, {0.3, 0.3, 1}, {0.3, -0.3, 1}}, 2, Rgb{});
    p.light = 0;
    s.lights.push_back({"lamp", {2}, Rgb::gray(3.0)});
    s.polygons.push_back(p);
    return s;
}

SolverOptions options() {
    SolverOptions o;
    o.epsilon = 1e-3;
    o.transfer.minRays = 16;
    o.transfer.maxRays = 16;
    return o;
}

/// A floor leaf with light links whose visibility is partial (a penumbra leaf).
int penumbraLeaf(const HierarchicalSolver& solver) {
    const auto& nodes = solver.hierarchy().nodes;
    for (int n = 0; n < static_cast<int>(nodes.size()); ++n) {
        if (nodes[n].isCluster() || !nodes[n].isLeaf() || nodes[n].polygon != 0) continue;
        const auto e = solver.lightExchange(n);
        if (e[0].F > 0 && e[0].FV > 0.05 * e[0].F && e[0].FV < 0.95 * e[0].F) return n;
    }
    return -1;
}

}  // namespace

TEST(SplitForLights, ChildrenShareTheLeafsFormFactorAndLinksGoPassive) {
    HierarchicalSolver solver(plateShadow(), options());
    solver.solve();
    const int leaf = penumbraLeaf(solver);
    ASSERT_GE(leaf, 0) << "the scene has no penumbra leaf on the floor";
    const auto before = solver.lightExchange(leaf);
    const size_t passive = solver.passiveLinks().size();
    std::vector<std::vector<HierarchicalSolver::LightExchange>> children;
    ASSERT_TRUE(solver.splitForLights(leaf, &children));
    ASSERT_EQ(children.size(), 4u);
    EXPECT_GT(solver.passiveLinks().size(), passive);
    // F is the receiver-to-source form factor, a quadrature over the receiver, times the
    // lamp's normalisation (normaliseLamps: the lamp delivers exactly its power), which
    // the children carry: their area-weighted mean is the parent's F, up to the quadrature
    // error (the same rule on 4 times as many points; 2e-3 relative at this distance).
    const auto& nodes = solver.hierarchy().nodes;
    const Node& parent = nodes[leaf];
    double meanF = 0;
    for (int k = 0; k < 4; ++k) {
        const Node& c = nodes[parent.firstChild + k];
        meanF += children[k][0].F * c.area / parent.area;
        EXPECT_GE(children[k][0].FV, 0.0);
        EXPECT_LE(children[k][0].FV, children[k][0].F * (1 + 1e-12));
    }
    EXPECT_NEAR(meanF, before[0].F, 2e-3 * before[0].F);
    // ... and the geometry is right: the lamp's scale is within a few per cent of 1 here
    // (its whole power reaches the floor and the plate), so the mean is within that of
    // a high-order reference.
    const Polygon& lamp = solver.scene().polygons[2];
    const double reference =
        polygonToPolygon(parent.v.data(), parent.vertexCount, parent.normal, lamp.v.data(),
                         static_cast<int>(lamp.v.size()), lamp.normal, 12);
    EXPECT_NEAR(meanF, reference, 0.03 * reference);
    EXPECT_TRUE(
        solver.linksOf(leaf).empty() ||
        std::none_of(solver.linksOf(leaf).begin(), solver.linksOf(leaf).end(), [&](const Link& l) {
            return solver.scene().polygons[nodes[l.source].polygon].light >= 0;
        }));
    for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(solver.lightExchange(parent.firstChild + k)[0].F, children[k][0].F, 1e-15);
}

TEST(SplitForLights, UnsplitRestoresTheLinksExactly) {
    HierarchicalSolver solver(plateShadow(), options());
    solver.solve();
    const auto& nodes = solver.hierarchy().nodes;
    std::vector<Rgb> B0;
    double maxB = 0;
    for (const Node& n : nodes) {
        B0.push_back(n.B);
        maxB = std::max(maxB, n.B.maxComponent());
    }
    const std::vector<Link> links = solver.links();
    const size_t passive = solver.passiveLinks().size();
    const size_t count = nodes.size();
    const int leaf = penumbraLeaf(solver);
    ASSERT_GE(leaf, 0);
    ASSERT_TRUE(solver.splitForLights(leaf));
    solver.gatherPushPull();  // the split changes the solution...
    solver.unsplit(leaf);     // ...and undoing it must give the same one back
    solver.gatherPushPull();
    ASSERT_EQ(nodes.size(), count);
    ASSERT_EQ(solver.links().size(), links.size());
    EXPECT_EQ(solver.passiveLinks().size(), passive);
    for (size_t i = 0; i < links.size(); ++i) {  // same links in the same (gather) order
        const Link &a = solver.links()[i], &b = links[i];
        EXPECT_TRUE(a.receiver == b.receiver && a.source == b.source && a.F == b.F && a.V == b.V)
            << "link " << i;
    }
    // The solution converges back to the same fixed point from the split one's values:
    // to the solver's tolerance (1e-4 of the total power), far below 1e-3 of the largest B.
    for (size_t n = 0; n < count; ++n)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(nodes[n].B[c], B0[n][c], 1e-3 * maxB) << n;
    EXPECT_THROW(solver.unsplit(leaf), std::logic_error);
}

TEST(SplitForLights, ClustersAndTinyLeavesAreNotSplit) {
    SolverOptions o = options();
    o.minArea = 100;  // larger than any element: nothing may be split
    HierarchicalSolver solver(plateShadow(), o);
    EXPECT_FALSE(solver.splitForLights(Hierarchy::kRoot));
    EXPECT_FALSE(solver.splitForLights(solver.hierarchy().polygonRoot[0]));
}

TEST(EdgeNeighbours, UniformGridHasTwoThreeOrFourNeighbours) {
    Scene s;
    s.objects = {"floor"};
    s.polygons.push_back(
        makePolygon({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}, 0, Rgb::gray(0.5)));
    Hierarchy h(s);
    const int root = h.polygonRoot[0];
    h.subdivide(root);
    for (int k = 0; k < 4; ++k) h.subdivide(h.nodes[root].firstChild + k);
    int corners = 0, sides = 0, inner = 0;
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        if (h.nodes[n].isCluster() || !h.nodes[n].isLeaf()) continue;
        const auto nb = h.edgeNeighbours(n);
        for (int m : nb) {  // symmetric, and really adjacent (centres 1 m apart)
            const auto back = h.edgeNeighbours(m);
            EXPECT_NE(std::find(back.begin(), back.end(), n), back.end());
            EXPECT_NEAR(glm::length(h.nodes[m].centre - h.nodes[n].centre), 1.0, 1e-12);
        }
        corners += nb.size() == 2;
        sides += nb.size() == 3;
        inner += nb.size() == 4;
    }
    EXPECT_EQ(corners, 4);
    EXPECT_EQ(sides, 8);
    EXPECT_EQ(inner, 4);
}

TEST(EdgeNeighbours, SmallLeavesFindTheLargeOneAcrossAnEdge) {
    Scene s;
    s.objects = {"floor"};
    s.polygons.push_back(
        makePolygon({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, 0, Rgb::gray(0.5)));
    Hierarchy h(s);
    const int root = h.polygonRoot[0];
    h.subdivide(root);
    // Split the child at the origin corner; its right neighbour stays large.
    int small = -1, large = -1;
    for (int k = 0; k < 4; ++k) {
        const Vec3 c = h.nodes[h.nodes[root].firstChild + k].centre;
        if (c.x < 1 && c.y < 1) small = h.nodes[root].firstChild + k;
        if (c.x > 1 && c.y < 1) large = h.nodes[root].firstChild + k;
    }
    ASSERT_TRUE(h.subdivide(small));
    int touching = 0;
    for (int k = 0; k < 4; ++k) {
        const int c = h.nodes[small].firstChild + k;
        if (h.nodes[c].centre.x < 0.5) continue;  // not on the shared edge x = 1
        ++touching;
        const auto nb = h.edgeNeighbours(c);
        EXPECT_NE(std::find(nb.begin(), nb.end(), large), nb.end());
    }
    EXPECT_EQ(touching, 2);
    // Nothing across the polygon's own boundary.
    for (int k = 0; k < 4; ++k)
        for (int m : h.edgeNeighbours(h.nodes[small].firstChild + k))
            EXPECT_EQ(h.nodes[m].polygon, 0);
}
