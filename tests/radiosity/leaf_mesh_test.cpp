// LeafMesh: shared leaf corners and interpolation from them.
#include <gtest/gtest.h>

#include "radiosity/detail/rng.h"
#include "radiosity/hierarchy.h"
#include "radiosity/leaf_mesh.h"
#include "tests/support/quad_and_triangle.h"

using namespace radiosity;
using radiosity::test::quadAndTriangle;

namespace {

Rgb linearField(const Vec3& x) {
    return {1 + x.x, 2 - 0.5 * x.y, 0.3 + x.z + x.x * 0.2};
}

}  // namespace

TEST(LeafMesh, SharedCornersAreOneVertex) {
    Hierarchy h(quadAndTriangle());
    // Two uniform levels on the quad: a 4 x 4 grid of leaves has 5 x 5 corners. The
    // triangle, one level: 4 leaves, 6 corners.
    const int q = h.polygonRoot[0];
    h.subdivide(q);
    for (int k = 0; k < 4; ++k) h.subdivide(h.nodes[q].firstChild + k);
    h.subdivide(h.polygonRoot[1]);
    const LeafMesh mesh(h);
    EXPECT_EQ(mesh.vertices().size(), 25u + 6u);
}

TEST(LeafMesh, InterpolationReproducesBilinearAndLinearFields) {
    // Bilinear interpolation on a quad leaf reproduces any field that is bilinear in the
    // leaf's parameters, and barycentric interpolation any linear field on a triangle.
    // A quadtree child's parameters are an affine function of its parent's, so a field
    // bilinear on the whole quad stays exact on every leaf: the check holds to rounding
    // (1e-9 allows the Gauss-Newton inverse to stop at 1e-12 in the parameters).
    Hierarchy h(quadAndTriangle());
    Rng rng(5);
    // Irregular subdivision: T-vertices included.
    h.subdivide(h.polygonRoot[0]);
    h.subdivide(h.nodes[h.polygonRoot[0]].firstChild + 2);
    h.subdivide(h.polygonRoot[1]);
    h.subdivide(h.nodes[h.polygonRoot[1]].firstChild + 3);
    const LeafMesh mesh(h);
    const Node& quad = h.nodes[h.polygonRoot[0]];
    // A field bilinear on the quad: evaluated by its parameters, not by position.
    auto bilinear = [](double s, double t) { return Rgb{1 + 2 * s, 3 * t - s * t, 0.5 + s}; };
    std::vector<Rgb> values(mesh.vertices().size());
    for (size_t v = 0; v < values.size(); ++v) {
        const auto& vx = mesh.vertices()[v];
        if (vx.polygon == 0) {
            // The corner's parameters on the root quad (it is a corner of a leaf).
            const auto w = mesh.weights(h.polygonRoot[0], vx.position);
            const double s = w[1] + w[2], t = w[2] + w[3];
            values[v] = bilinear(s, t);
        } else {
            values[v] = linearField(vx.position);
        }
    }
    for (int i = 0; i < 200; ++i) {
        const double u = rng.uniform(), v = rng.uniform();
        const Vec3 xq = pointOnElement(quad, u, v);
        const Rgb bq = mesh.interpolate(values, 0, xq);
        const Rgb eq = bilinear(u, v);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(bq[c], eq[c], 1e-9);
        const Vec3 xt = pointOnElement(h.nodes[h.polygonRoot[1]], u, v);
        const Rgb bt = mesh.interpolate(values, 1, xt);
        const Rgb et = linearField(xt);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(bt[c], et[c], 1e-9);
    }
}

TEST(LeafMesh, SplitLeavesHaveTheCornersOfTheirPieces) {
    // The quad's 2 x 2 leaves, each split twice: as many vertices as an 8 x 8 grid of
    // leaves (9 x 9), the leaves' shared edges counted once. The triangle split once and
    // not subdivided: the 6 corners of its 4 pieces. A leaf's vertexIds are its pieces'
    // corners: (2^2 + 1)^2 on a quad.
    Hierarchy h(quadAndTriangle());
    const int q = h.polygonRoot[0];
    h.subdivide(q);
    const LeafMesh mesh(h, [&](int leaf) { return h.nodes[leaf].polygon == 0 ? 2 : 1; });
    EXPECT_EQ(mesh.vertices().size(), 9u * 9u + 6u);
    EXPECT_EQ(mesh.vertexIds(h.nodes[q].firstChild).size(), 25u);
    EXPECT_EQ(mesh.vertexIds(h.polygonRoot[1]).size(), 6u);
    EXPECT_EQ(mesh.splits(h.polygonRoot[1]), 1);
}

TEST(LeafMesh, SplitLeafMeetsItsSubdividedNeighbourWithoutATVertex) {
    // A leaf split once has, on its edges, the midpoints that a subdivided neighbour has as
    // corners: the quad cut into 2 x 2 leaves with one leaf subdivided again, the other
    // three split once, is the 4 x 4 grid of corners (25), no more.
    Hierarchy h(quadAndTriangle());
    const int q = h.polygonRoot[0];
    h.subdivide(q);
    h.subdivide(h.nodes[q].firstChild);
    const LeafMesh mesh(h, [&](int leaf) { return h.nodes[leaf].parent == q ? 1 : 0; });
    EXPECT_EQ(mesh.vertices().size(), 25u + 3u);
}

TEST(LeafMesh, SplitInterpolationIsPiecewiseLinearAndContinuous) {
    // Split leaves reproduce the same fields as whole ones (bilinear on a quad's
    // parameters, linear on a triangle), with any number of splits: every piece is a
    // sub-patch of the leaf's own map. And a field that is only known at the vertices
    // (random values) is continuous across the pieces' edges: two points 1e-9 apart on
    // either side of a piece's edge interpolate to values 1e-6 apart at most.
    Hierarchy h(quadAndTriangle());
    h.subdivide(h.polygonRoot[1]);
    for (int splits : {1, 2, 3}) {
        const LeafMesh mesh(h, [&](int) { return splits; });
        std::vector<Rgb> values(mesh.vertices().size()), noise(values.size());
        Rng rng(11 + splits);
        for (size_t v = 0; v < values.size(); ++v) {
            const auto& vx = mesh.vertices()[v];
            if (vx.polygon == 0) {
                const auto w = mesh.weights(h.polygonRoot[0], vx.position);
                values[v] = Rgb{1 + 2 * (w[1] + w[2]), 3 * (w[2] + w[3]), 0.5};
            } else {
                values[v] = linearField(vx.position);
            }
            noise[v] = Rgb::gray(rng.uniform());
        }
        for (int i = 0; i < 200; ++i) {
            const double u = rng.uniform(), v = rng.uniform();
            const Vec3 xq = pointOnElement(h.nodes[h.polygonRoot[0]], u, v);
            const Rgb bq = mesh.interpolate(values, 0, xq);
            EXPECT_NEAR(bq.r, 1 + 2 * u, 1e-9) << splits;
            EXPECT_NEAR(bq.g, 3 * v, 1e-9) << splits;
            const Vec3 xt = pointOnElement(h.nodes[h.polygonRoot[1]], u, v);
            const Rgb bt = mesh.interpolate(values, 1, xt);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(bt[c], linearField(xt)[c], 1e-9) << splits;
        }
        // Continuity across the quad's piece edges at s = k / 2^splits.
        const Node& quad = h.nodes[h.polygonRoot[0]];
        const int side = 1 << splits;
        for (int k = 1; k < side; ++k)
            for (int i = 0; i < 20; ++i) {
                const double s = static_cast<double>(k) / side, t = rng.uniform();
                const Rgb a = mesh.interpolate(noise, 0, pointOnElement(quad, s - 1e-9, t));
                const Rgb b = mesh.interpolate(noise, 0, pointOnElement(quad, s + 1e-9, t));
                EXPECT_NEAR(a.r, b.r, 1e-6) << splits << " " << k;
            }
    }
}
