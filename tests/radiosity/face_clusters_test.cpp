// Face clusters (face_clusters.h) and the hierarchy built over them (hierarchy.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>

#include "radiosity/face_clusters.h"
#include "radiosity/hierarchy.h"
#include "radiosity/solver.h"
#include "tests/support/grids.h"

using namespace radiosity;

namespace {

/// A quad (corners counter-clockwise from its front) cut into an n x n grid of triangle
/// pairs that share their corners, as a reconstruction's mesh does.
void addGrid(Scene& s, const std::array<Vec3, 4>& q, int n, int object, double rho = 0.5) {
    const auto at = [&](int i, int j) {
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        return (1 - u) * (1 - v) * q[0] + u * (1 - v) * q[1] + u * v * q[2] + (1 - u) * v * q[3];
    };
    test::addTriangleGrid(s, n, at, object, Rgb::gray(rho));
}

/// The inside of a closed 1 m box, every face cut into an n x n grid, facing in.
Scene cutBox(int n) {
    Scene s;
    s.objects = {"box"};
    const Vec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int faces[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                             {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};
    for (const auto& f : faces) addGrid(s, {c[f[0]], c[f[1]], c[f[2]], c[f[3]]}, n, 0);
    return s;
}

/// The polygons of each face cluster (the forest's roots).
std::vector<std::vector<int>> patchesOf(const FaceClusterForest& f) {
    std::vector<std::vector<int>> out;
    for (int root : f.roots) {
        out.emplace_back();
        f.polygonsUnder(root, out.back());
    }
    return out;
}

}  // namespace

TEST(FaceClusters, AFlatGridIsOnePatchAndEveryPolygonIsInExactlyOne) {
    Scene s;
    s.objects = {"floor"};
    addGrid(s, {Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{2, 1, 0}, Vec3{0, 1, 0}}, 12, 0);
    const FaceClusterForest f = buildFaceClusters(s.polygons);
    ASSERT_EQ(f.roots.size(), 1u);
    // A binary forest over n polygons with r roots has n - r merges.
    EXPECT_EQ(f.merges.size(), s.polygons.size() - 1);
    std::vector<int> members;
    f.polygonsUnder(f.roots[0], members);
    std::sort(members.begin(), members.end());
    for (size_t i = 0; i < members.size(); ++i) EXPECT_EQ(members[i], static_cast<int>(i));
}

TEST(FaceClusters, TheBoxsSixFacesAreSixPatches) {
    // Faces meet at 90 degrees, far beyond the 30-degree cone: no patch crosses an edge.
    const Scene s = cutBox(6);
    const FaceClusterForest f = buildFaceClusters(s.polygons);
    const auto patches = patchesOf(f);
    ASSERT_EQ(patches.size(), 6u);
    for (const auto& p : patches) {
        EXPECT_EQ(p.size(), 72u);  // one face's 6 x 6 x 2 triangles
        for (int q : p) EXPECT_GT(glm::dot(s.polygons[q].normal, s.polygons[p[0]].normal), 0.999);
    }
}

TEST(FaceClusters, ACurvedSurfaceSplitsIntoPatchesWithinTheCone) {
    // A half cylinder of radius 1 m in 48 strips of a triangle pair: its normals turn
    // through 180 degrees and a patch's through at most twice the cone's half-angle, so it
    // needs at least 180 / 60 = 3 patches; each patch's normals must lie within the cone
    // about its mean normal (the merge's bound is conservative: never narrower).
    Scene s;
    s.objects = {"vault"};
    const int strips = 48;
    for (int k = 0; k < strips; ++k) {
        const double a0 = std::numbers::pi * k / strips, a1 = std::numbers::pi * (k + 1) / strips;
        const Vec3 p0{std::cos(a0), 0, std::sin(a0)}, p1{std::cos(a1), 0, std::sin(a1)};
        // Seen from inside (the axis), counter-clockwise: the front faces the axis.
        addGrid(s, {p0, p0 + Vec3{0, 2, 0}, p1 + Vec3{0, 2, 0}, p1}, 1, 0);
    }
    const FaceClusterOptions options;
    const FaceClusterForest f = buildFaceClusters(s.polygons, options);
    const auto patches = patchesOf(f);
    EXPECT_GE(patches.size(), 3u);
    EXPECT_LT(patches.size(), 24u);  // and they do merge: far fewer than the 48 strips
    for (const auto& p : patches) {
        Vec3 mean{0, 0, 0};
        for (int q : p) mean += s.polygons[q].area * s.polygons[q].normal;
        mean = glm::normalize(mean);
        for (int q : p)
            EXPECT_LE(std::acos(std::clamp(glm::dot(mean, s.polygons[q].normal), -1.0, 1.0)),
                      options.maxConeAngle + 1e-9);
    }
}

TEST(FaceClusters, DroppingStaleCandidatesChangesNoMerge) {
    // A jittered dome of 2 x 40 x 40 triangles, as a reconstruction cuts a curved surface:
    // the heap's stale candidates dropped at every chance, and never, must give the same
    // forest, merge for merge (the live candidates decide each merge).
    Scene s;
    s.objects = {"dome"};
    const int n = 40;
    const auto at = [&](int i, int j) {
        const double u = 2.0 * i / n - 1, v = 2.0 * j / n - 1;
        const double jitter = 0.004 * std::sin(12.9898 * i + 78.233 * j);
        return Vec3{u + jitter, v - jitter, 1 - 0.4 * (u * u + v * v) + jitter};
    };
    test::addTriangleGrid(s, n, at, 0, Rgb::gray(0.5));
    FaceClusterOptions often, never;
    often.dropStaleAbove = 0;
    never.dropStaleAbove = std::numeric_limits<size_t>::max();
    const FaceClusterForest a = buildFaceClusters(s.polygons, often);
    const FaceClusterForest b = buildFaceClusters(s.polygons, never);
    ASSERT_GT(a.merges.size(), 100u);  // the dome does cluster
    EXPECT_EQ(a.merges, b.merges);
    EXPECT_EQ(a.roots, b.roots);
}

TEST(FaceClusters, NeverJoinsObjectsLampsOrTheTwoSidesOfASheet) {
    Scene s;
    s.objects = {"a", "b", "sheet"};
    const std::array<Vec3, 4> c{Vec3{0, 0, 0}, Vec3{1, 0, 0}, Vec3{1, 1, 0}, Vec3{0, 1, 0}};
    addGrid(s, c, 2, 0);
    addGrid(s, {c[1], Vec3{2, 0, 0}, Vec3{2, 1, 0}, c[2]}, 2, 1);  // coplanar, other object
    // A thin sheet: the same triangles twice, back to back.
    const size_t sheet = s.polygons.size();
    addGrid(s, {Vec3{0, 0, 1}, Vec3{1, 0, 1}, Vec3{1, 1, 1}, Vec3{0, 1, 1}}, 2, 2);
    addGrid(s, {Vec3{0, 0, 1}, Vec3{0, 1, 1}, Vec3{1, 1, 1}, Vec3{1, 0, 1}}, 2, 2);
    // A lamp's face beside the first grid, coplanar and sharing its edge.
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(1)});
    // (The grid's edge from (0, 0.5) to (0, 0) is one of its sides.)
    s.polygons.push_back(
        makePolygon({Vec3{0, 0, 0}, Vec3{0, 0.5, 0}, Vec3{-0.5, 0.25, 0}}, 0, Rgb{}));
    s.polygons.back().light = 0;
    const FaceClusterForest f = buildFaceClusters(s.polygons);
    for (const auto& p : patchesOf(f)) {
        std::set<int> objects;
        for (int q : p) objects.insert(s.polygons[q].object);
        EXPECT_EQ(objects.size(), 1u);
        if (p.size() > 1) {
            for (int q : p) EXPECT_LT(s.polygons[q].light, 0) << "a lamp's face merged";
        }
        if (s.polygons[p[0]].object == 2) {
            for (int q : p)
                EXPECT_GT(glm::dot(s.polygons[q].normal, s.polygons[p[0]].normal), 0)
                    << "the two sides of the sheet merged";
        }
    }
    EXPECT_EQ(patchesOf(f).size(), 5u);  // a, b, the sheet's two sides, the lamp
    EXPECT_EQ(s.polygons[sheet].object, 2);
}

TEST(FaceClusters, TheHierarchyKeepsEachPatchContiguousUnderItsNode) {
    const Scene s = cutBox(5);
    const Hierarchy h(s);
    EXPECT_EQ(h.faceClusterCount(), 6);
    std::set<int> nodes(h.polygonPatch.begin(), h.polygonPatch.end());
    ASSERT_EQ(nodes.size(), 6u);
    for (int node : nodes) {
        ASSERT_GE(node, 0);
        const Node& c = h.nodes[node];
        ASSERT_TRUE(c.isCluster());
        EXPECT_EQ(c.polyEnd - c.polyBegin, 50);
        for (int i = c.polyBegin; i < c.polyEnd; ++i)
            EXPECT_EQ(h.polygonPatch[h.polygonOrder[i]], node);
        // Every cluster under a patch is planar: its cone is 0 to rounding.
        EXPECT_LT(h.coneAngle(c), 1e-6);
    }
    // Every polygon has one root element, the cluster ranges cover the polygons once.
    std::vector<int> order = h.polygonOrder;
    std::sort(order.begin(), order.end());
    for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], static_cast<int>(i));
    for (size_t p = 0; p < s.polygons.size(); ++p)
        EXPECT_EQ(h.nodes[h.polygonRoot[p]].polygon, int(p));
}

TEST(FaceClusters, SeenIsMeasuredPerPatchInAClosedBox) {
    // In a closed box every leaf sees the box's front faces in every direction: 1 exactly,
    // whether measured per triangle or per face cluster. Opening the top (its triangles
    // gone) leaves the floor's patch seeing the box's sides only: the unoccluded view
    // factor from a unit square to its four unit walls, 1 - F(floor -> top) = 1 - 0.19982
    // (Howell's parallel squares at distance 1) plus what it sees of the lamp's front
    // (0.2 m square 1 m up: about 0.010), to within the rays' 4 standard errors.
    Scene closed = cutBox(4);
    closed.lights.push_back({"lamp", {}, Rgb::gray(10)});
    const double h0 = 0.999;
    closed.lights[0].polygons.push_back(static_cast<int>(closed.polygons.size()));
    closed.polygons.push_back(makePolygon(
        {Vec3{0.4, 0.4, h0}, Vec3{0.4, 0.6, h0}, Vec3{0.6, 0.6, h0}, Vec3{0.6, 0.4, h0}}, 0,
        Rgb{}));
    closed.polygons.back().light = 0;
    SolverOptions o;
    o.epsilon = 1e-2;
    HierarchicalSolver solver(closed, o);
    solver.solve();
    // The floor sees the box or the lamp's front in every direction. (The ceiling's patch
    // sees the lamp's back, 1 mm below it, in a few percent of its rays.)
    int measured = 0;
    for (const Node& n : solver.hierarchy().nodes)
        if (!n.isCluster() && n.isLeaf() && n.polygon >= 0 &&
            closed.polygons[n.polygon].light < 0) {
            ++measured;
            if (closed.polygons[n.polygon].normal.z > 0.5) {
                EXPECT_DOUBLE_EQ(n.seen, 1.0);
            }
            EXPECT_GT(n.seen, 0.9);
        }
    EXPECT_GT(measured, 0);

    Scene open = closed;
    std::vector<Polygon> kept;
    for (const Polygon& p : open.polygons)
        if (!(p.light < 0 && p.normal.z < -0.5)) kept.push_back(p);  // the top, facing down
    open.polygons = kept;
    open.lights[0].polygons = {static_cast<int>(open.polygons.size()) - 1};
    HierarchicalSolver openSolver(open, o);
    openSolver.solve();
    const auto& h = openSolver.hierarchy();
    int floorLeaves = 0;
    for (const Node& n : h.nodes) {
        if (n.isCluster() || !n.isLeaf() || n.polygon < 0 || open.polygons[n.polygon].light >= 0)
            continue;
        if (open.polygons[n.polygon].normal.z < 0.5 ||
            h.polygonRoot[n.polygon] != int(&n - &h.nodes[0]))
            continue;
        ++floorLeaves;
        EXPECT_NEAR(n.seen, 1 - 0.19982 + 0.010, 4 * n.seenError + 0.005);
    }
    EXPECT_GT(floorLeaves, 0);
}
