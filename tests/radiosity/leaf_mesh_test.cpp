// LeafMesh: shared leaf corners and interpolation from them.
#include <gtest/gtest.h>

#include "radiosity/hierarchy.h"
#include "radiosity/leaf_mesh.h"
#include "radiosity/rng.h"

using namespace radiosity;

namespace {

/// A skewed convex quad (not a parallelogram, so the bilinear map is not affine) and a
/// triangle, on two objects.
Scene quadAndTriangle() {
    Scene s;
    s.objects = {"quad", "tri"};
    s.polygons.push_back(
        makePolygon({{0, 0, 0}, {2, 0.2, 0}, {1.7, 1.5, 0}, {0.1, 1.1, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(makePolygon({{0, 0, 1}, {1, 0, 1.5}, {0, 1, 1}}, 1, Rgb::gray(0.5)));
    return s;
}

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
