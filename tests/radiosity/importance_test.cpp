// Camera importance (HierarchicalSolver::setCameraImportance; Smits, Arvo & Salesin 1992):
// the refinement spends less on what the camera does not see, and the one bounce keeps
// the surfaces that light what it sees above the floor.
#include <gtest/gtest.h>

#include "furnace.h"
#include "radiosity/solver.h"

using namespace radiosity;

namespace {

/// A 6 x 3 x 3 m room (faces inward, reflectance 0.6: floor 0, ceiling 1, walls y = 0
/// (2), y = 3 (3), x = 0 (4), x = 6 (5)) lit by a 0.5 m lamp under the ceiling's middle.
Scene room() {
    Scene s;
    s.objects = {"room", "lamp"};
    for (const auto& f : test::boxFacesInward(6, 3, 3))
        s.polygons.push_back(makePolygon(f, 0, Rgb::gray(0.6)));
    Polygon lamp = makePolygon(
        {{2.75, 1.25, 2.9}, {2.75, 1.75, 2.9}, {3.25, 1.75, 2.9}, {3.25, 1.25, 2.9}}, 1, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(20.0)});
    s.polygons.push_back(lamp);
    return s;
}

int leavesOf(const HierarchicalSolver& solver, int polygon) {
    int n = 0;
    for (const Node& node : solver.hierarchy().nodes)
        n += !node.isCluster() && node.isLeaf() && node.polygon == polygon ? 1 : 0;
    return n;
}

}  // namespace

TEST(CameraImportance, TheWallBehindTheCameraCostsLessAndKeepsItsBounce) {
    SolverOptions o;
    o.epsilon = 1e-4;
    HierarchicalSolver plain(room(), o);
    plain.solve();
    HierarchicalSolver weighed(room(), o);
    // The camera sees every face but the wall x = 0, behind it (and the lamp's face).
    std::vector<double> seen = {1, 1, 1, 1, 0, 1, 0};
    weighed.setCameraImportance(seen);
    // Before any link: the direct importance, the floor where nothing is seen.
    EXPECT_EQ(weighed.importanceOf(Hierarchy::kRoot), 1.0);
    weighed.solve();
    // The wall behind the camera is refined less: its receivers' errors count at their
    // importance, below 1 (the plain solve refines it as much as the opposite wall).
    EXPECT_LT(leavesOf(weighed, 4), leavesOf(plain, 4));
    EXPECT_EQ(leavesOf(plain, 4), leavesOf(plain, 5));  // the room is symmetric about x = 3
    // Its light reaches the seen faces: after the bounce its importance is the mean over
    // where its light goes of rho times the seen share: every face it sees but the lamp
    // (1 % of its hemisphere from the wall's centre, less from its corners) is seen and
    // reflects 0.6, so 0.6 (1 - 0.01) <= I <= 0.6, far above the floor.
    int wallElement = -1;
    for (size_t n = 0; n < weighed.hierarchy().nodes.size(); ++n)
        if (!weighed.hierarchy().nodes[n].isCluster() && weighed.hierarchy().nodes[n].polygon == 4)
            wallElement = static_cast<int>(n);
    ASSERT_GE(wallElement, 0);
    const double I = weighed.importanceOf(wallElement);
    EXPECT_GE(I, 0.6 * 0.99);
    EXPECT_LE(I, 0.6 + 1e-12);
}
