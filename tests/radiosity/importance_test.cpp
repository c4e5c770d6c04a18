// Camera importance (HierarchicalSolver::setCameraImportance; Smits, Arvo & Salesin 1992):
// the refinement spends less on what the camera does not see, and the one bounce keeps
// the surfaces that light what it sees above the floor.
#include <gtest/gtest.h>

#include <numbers>
#include <stdexcept>

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

namespace {

/// Two 1 x 1 m squares on z = 0, 3 m apart, facing up (reflectance 0.5), and a 0.5 m lamp
/// facing down 2 m above the first, of radiance `lamp` (0: no lamp).
Scene twoSquares(double lamp) {
    Scene s;
    s.objects = {"ground", "lamp"};
    s.polygons.push_back(
        makePolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(
        makePolygon({{3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}}, 0, Rgb::gray(0.5)));
    if (lamp > 0) {
        Polygon p = makePolygon(
            {{0.25, 0.25, 2}, {0.25, 0.75, 2}, {0.75, 0.75, 2}, {0.75, 0.25, 2}}, 1, Rgb{});
        p.light = 0;
        s.lights.push_back({"lamp", {2}, Rgb::gray(lamp)});
        s.polygons.push_back(p);
    }
    return s;
}

}  // namespace

TEST(SeenPower, TheThresholdFollowsThePowerThatReachesWhatTheCameraSees) {
    // A sun straight overhead with a hard disc lights both squares fully: every point of
    // each receives E exactly, so the seen share is exact.
    const double E = 4;
    HierarchicalSolver solver(twoSquares(0), SolverOptions{});
    solver.addEmitter(makeSun("sun", {0, 0, 1}, 0, Rgb::gray(E)));
    EXPECT_EQ(solver.seenPowerShare(), 1.0);  // no camera: all of the power
    solver.setCameraSeen({1, 0});
    EXPECT_NEAR(solver.seenPowerShare(), 0.5, 1e-12);
    solver.setCameraSeen({1, 1});
    EXPECT_NEAR(solver.seenPowerShare(), 1.0, 1e-12);
    // Nothing lit is seen: the floor, not 0 (a threshold of 0 would refine without end).
    solver.setCameraSeen({0, 0});
    EXPECT_EQ(solver.seenPowerShare(), SolverOptions{}.seenPowerFloor);
    EXPECT_THROW(solver.setCameraSeen({1}), std::invalid_argument);
}

TEST(SeenPower, ALampsPowerCountsInFullAndAFloorOfOneIsThePlainCriterion) {
    // The lamp's emitted power pi L A, against the sun's E on each square (1 m^2): the share
    // (E + pi L A) / (2 E + pi L A).
    const double E = 4, L = 10, lampPower = std::numbers::pi * L * 0.25;
    HierarchicalSolver solver(twoSquares(L), SolverOptions{});
    solver.addEmitter(makeSun("sun", {0, 0, 1}, 0, Rgb::gray(E)));
    solver.setCameraSeen({1, 0, 0});
    // The lamp's square, the first, is shaded from the sun by the lamp (0.25 m^2 of it).
    const double firstSun = E * 0.75;
    EXPECT_NEAR(solver.seenPowerShare(), (firstSun + lampPower) / (firstSun + E + lampPower), 1e-9);
    SolverOptions plain;
    plain.seenPowerFloor = 1;
    HierarchicalSolver off(twoSquares(L), plain);
    off.addEmitter(makeSun("sun", {0, 0, 1}, 0, Rgb::gray(E)));
    off.setCameraSeen({1, 0, 0});
    EXPECT_EQ(off.seenPowerShare(), 1.0);
}
