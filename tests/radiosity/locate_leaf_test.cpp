// Hierarchy::locateLeaf: the leaf holding a point, found from each parent's cut lines.
#include <gtest/gtest.h>

#include "radiosity/detail/rng.h"
#include "radiosity/hierarchy.h"
#include "tests/support/quad_and_triangle.h"

using namespace radiosity;
using radiosity::test::quadAndTriangle;

namespace {

/// Subdivides unevenly, as refinement does: each leaf is cut with probability `p` down to
/// `depth` levels.
void subdivideUnevenly(Hierarchy& h, int node, int depth, double p, Rng& rng) {
    if (depth == 0 || rng.uniform() > p || !h.subdivide(node)) return;
    const int first = h.nodes[node].firstChild;
    for (int k = 0; k < 4; ++k) subdivideUnevenly(h, first + k, depth - 1, p, rng);
}

}  // namespace

TEST(LocateLeaf, AgreesWithTheLeavesThatContainThePoint) {
    // Every random point of either polygon must land in a leaf whose own corners contain it
    // (a containment test on the leaf alone, independent of how the descent chose): the
    // descent reads only the parents' cut lines. Tolerance 1e-9 m, as elementContains uses:
    // far below any leaf here (the smallest is 2^-8 of a 2 m quad) and above rounding.
    Hierarchy h(quadAndTriangle());
    Rng rng{7};
    for (int p = 0; p < 2; ++p) subdivideUnevenly(h, h.polygonRoot[p], 8, 0.8, rng);
    for (int p = 0; p < 2; ++p) {
        const Node& root = h.nodes[h.polygonRoot[p]];
        int leavesHit = 0;
        std::vector<char> hit(h.nodes.size(), 0);
        for (int i = 0; i < 20000; ++i) {
            // A uniform point of the polygon: a triangle fan from corner 0.
            const int t = root.vertexCount == 4 && rng.uniform() < 0.5 ? 2 : 1;
            double a = rng.uniform(), b = rng.uniform();
            if (a + b > 1) a = 1 - a, b = 1 - b;
            const Vec3 x =
                root.v[0] + a * (root.v[t] - root.v[0]) + b * (root.v[t + 1] - root.v[0]);
            const int leaf = h.locateLeaf(p, x);
            ASSERT_TRUE(h.nodes[leaf].isLeaf());
            ASSERT_EQ(h.nodes[leaf].polygon, p);
            ASSERT_TRUE(elementContains(h.nodes[leaf], x, 1e-9))
                << "polygon " << p << " point " << x.x << "," << x.y << "," << x.z;
            leavesHit += hit[leaf] ? 0 : 1;
            hit[leaf] = 1;
        }
        EXPECT_GT(leavesHit, 100) << "the subdivision reached too few leaves to test";
    }
}

TEST(LocateLeaf, PointsJustOutsideGoToTheLeafBeside) {
    // A point a hair outside an edge (a ray hit rounded off the polygon) goes to the leaf on
    // that edge, not to a far one: the leaf's distance to it is at most the offset.
    Hierarchy h(quadAndTriangle());
    Rng rng{11};
    subdivideUnevenly(h, h.polygonRoot[0], 6, 1.0, rng);
    const Node& root = h.nodes[h.polygonRoot[0]];
    for (int e = 0; e < 4; ++e) {
        const Vec3 a = root.v[e], b = root.v[(e + 1) % 4];
        const Vec3 out = glm::normalize(glm::cross(b - a, root.normal));
        for (double t : {0.1, 0.37, 0.5, 0.81}) {
            const Vec3 edgePoint = a + t * (b - a);
            const int leaf = h.locateLeaf(0, edgePoint + 1e-7 * out);
            EXPECT_TRUE(elementContains(h.nodes[leaf], edgePoint, 1e-6))
                << "edge " << e << " t " << t;
        }
    }
}
