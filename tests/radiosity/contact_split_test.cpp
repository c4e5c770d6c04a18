// splitAtContacts (radiosity/contact_split.h): polygons cut where other surfaces meet them,
// so that no element straddles a wall (Baum et al. 1991's light leaks).
#include "radiosity/contact_split.h"

#include <gtest/gtest.h>

#include <cmath>

#include "radiosity/solver.h"

using namespace radiosity;

namespace {

Polygon quad(std::vector<Vec3> q, int object = 0) {
    return makePolygon(q, object, Rgb::gray(0.5));
}

double totalArea(const std::vector<Polygon>& p, size_t from = 0) {
    double a = 0;
    for (size_t i = from; i < p.size(); ++i) a += p[i].area;
    return a;
}

/// A 2 x 2 m floor (+z) and a 1 m high wall standing on it along x = xWall, facing -x, from
/// y = y0 to y = y1.
std::vector<Polygon> floorAndWall(double xWall, double y0, double y1) {
    return {quad({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, 0),
            quad({{xWall, y0, 0}, {xWall, y1, 0}, {xWall, y1, 1}, {xWall, y0, 1}}, 1)};
}

}  // namespace

TEST(ContactSplit, AFloorIsCutWhereAWallStandsAcrossIt) {
    std::vector<Polygon> p = floorAndWall(0.7, 0, 2);
    const ContactSplitReport r = splitAtContacts(p, p.size());
    EXPECT_EQ(r.polygonsCut, 1);  // the floor; the wall's edges lie on the floor's boundary
    EXPECT_EQ(r.lines, 1);
    ASSERT_EQ(p.size(), 3u);
    // The floor's pieces: in place and appended, its area, normal, object and reflectance.
    EXPECT_NEAR(p[0].area + p[2].area, 4.0, 1e-12);
    for (const size_t i : {size_t{0}, size_t{2}}) {
        EXPECT_NEAR(p[i].normal.z, 1.0, 1e-12);
        EXPECT_EQ(p[i].object, 0);
        EXPECT_EQ(p[i].rho, Rgb::gray(0.5));
        // Each piece on one side of the wall's plane.
        double lo = 1e9, hi = -1e9;
        for (int k = 0; k < p[i].vertexCount; ++k) {
            lo = std::min(lo, p[i].v[static_cast<size_t>(k)].x);
            hi = std::max(hi, p[i].v[static_cast<size_t>(k)].x);
        }
        EXPECT_TRUE(hi <= 0.7 + 1e-12 || lo >= 0.7 - 1e-12) << lo << " " << hi;
    }
    EXPECT_NEAR(p[1].area, 2.0, 1e-12);  // the wall as it was
}

TEST(ContactSplit, AWallIsCutWhereASlabEndsOnIt) {
    // A slab at z = 0.4 ends against the wall: the slab's edge lies in the wall's interior.
    std::vector<Polygon> p = {
        quad({{1, 0, 0}, {1, 2, 0}, {1, 2, 1}, {1, 0, 1}}, 0),           // wall, facing -x
        quad({{0, 0, 0.4}, {1, 0, 0.4}, {1, 2, 0.4}, {0, 2, 0.4}}, 1)};  // slab, facing +z
    const ContactSplitReport r = splitAtContacts(p, p.size());
    EXPECT_EQ(r.polygonsCut, 1);
    ASSERT_EQ(p.size(), 3u);
    EXPECT_NEAR(p[0].area + p[2].area, 2.0, 1e-12);
    EXPECT_NEAR(std::min(p[0].area, p[2].area), 0.8, 1e-12);  // below the slab: 2 x 0.4
}

TEST(ContactSplit, EdgesOnABoundaryShortEdgesDecalsAndLightsCutNothing) {
    // Two triangles of one square share their diagonal: on both boundaries.
    std::vector<Polygon> square = {makePolygon({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}, 0, {}),
                                   makePolygon({{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}, 0, {})};
    EXPECT_EQ(splitAtContacts(square, square.size()).polygonsCut, 0);
    EXPECT_EQ(square.size(), 2u);
    // A wall 1 cm long (below minEdge of the 2 m scene's diagonal) cuts nothing.
    std::vector<Polygon> shortWall = floorAndWall(0.7, 1.0, 1.01);
    EXPECT_EQ(splitAtContacts(shortWall, shortWall.size()).polygonsCut, 0);
    // A lamp's face is neither cut nor cuts.
    std::vector<Polygon> lit = floorAndWall(0.7, 0, 2);
    lit[1].light = 0;
    EXPECT_EQ(splitAtContacts(lit, lit.size()).polygonsCut, 0);
    lit = floorAndWall(0.7, 0, 2);
    lit[0].light = 0;
    EXPECT_EQ(splitAtContacts(lit, lit.size()).polygonsCut, 0);
    // Polygons from `count` on (a scene's lights) are left out.
    std::vector<Polygon> later = floorAndWall(0.7, 0, 2);
    EXPECT_EQ(splitAtContacts(later, 1).polygonsCut, 0);
    // A triangle lying on the floor (a decal) divides nothing, though its edge crosses it.
    std::vector<Polygon> decal = {quad({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}),
                                  makePolygon({{2, 0, 0}, {0, 2, 0}, {0, 0, 0}}, 1, {})};
    EXPECT_EQ(splitAtContacts(decal, decal.size()).polygonsCut, 0);
    // Nothing at all.
    std::vector<Polygon> none;
    EXPECT_EQ(splitAtContacts(none, 0).polygonsCut, 0);
}

TEST(ContactSplit, APolygonIsCutIntoAtMostMaxPieces) {
    // Ten walls across the floor would make 11 strips; at most 4 pieces.
    std::vector<Polygon> p = {quad({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}})};
    for (int i = 1; i <= 10; ++i) {
        const double x = 0.18 * i;
        p.push_back(quad({{x, 0, 0}, {x, 2, 0}, {x, 2, 1}, {x, 0, 1}}, 1));
    }
    ContactSplitOptions o;
    o.maxPieces = 4;
    const ContactSplitReport r = splitAtContacts(p, p.size(), o);
    EXPECT_EQ(r.piecesLimited, 1);
    EXPECT_EQ(r.piecesAdded, 3);
    EXPECT_NEAR(p[0].area + totalArea(p, 11), 4.0, 1e-12);
}

namespace {

/// A closed 4 x 1 x 1 m box, all faces inward, divided at x = 1.7 by a partition wall that
/// stands on the floor and meets the ceiling (one-sided, facing the lamp): floor, ceiling and
/// the long walls are single polygons that run under, over and past it. A lamp under the
/// ceiling lights the part x < 1.7; the part beyond is closed off: no light reaches it.
Scene dividedBox() {
    Scene s;
    s.objects = {"box", "lamp"};
    const Rgb rho = Rgb::gray(0.6);
    auto add = [&](std::vector<Vec3> q) { s.polygons.push_back(makePolygon(q, 0, rho)); };
    add({{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {0, 1, 0}});          // floor
    add({{0, 0, 1}, {0, 1, 1}, {4, 1, 1}, {4, 0, 1}});          // ceiling
    add({{0, 0, 0}, {0, 0, 1}, {4, 0, 1}, {4, 0, 0}});          // y = 0
    add({{0, 1, 0}, {4, 1, 0}, {4, 1, 1}, {0, 1, 1}});          // y = 1
    add({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});          // x = 0
    add({{4, 0, 0}, {4, 0, 1}, {4, 1, 1}, {4, 1, 0}});          // x = 4
    add({{1.7, 0, 0}, {1.7, 0, 1}, {1.7, 1, 1}, {1.7, 1, 0}});  // the partition, facing -x
    Polygon lamp = makePolygon(
        {{0.6, 0.3, 0.99}, {0.6, 0.7, 0.99}, {1.0, 0.7, 0.99}, {1.0, 0.3, 0.99}}, 1, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(10.0)});
    s.polygons.push_back(lamp);
    return s;
}

/// The power the leaves beyond the partition reflect, over the power of those before it.
double closedOffShare(const Scene& scene) {
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver solver(scene, o);
    solver.solve();
    double beyond = 0, before = 0;
    for (const Node& e : solver.hierarchy().nodes) {
        if (e.isCluster() || !e.isLeaf() || e.emitting) continue;
        const double p = e.B.maxComponent() * e.area;
        (e.centre.x > 1.7 ? beyond : before) += p;
    }
    return before > 0 ? beyond / before : 1.0;
}

}  // namespace

TEST(ContactSplit, NoLightLeaksUnderAPartition) {
    // Uncut, every element of the floor, the ceiling and the long walls that straddles
    // x = 1.7 gathers on its lit side and reflects on the other (the leak is there to begin
    // with, or this test shows nothing). Cut, the closed-off part is lit by nothing but the
    // clusters' links, whose rays the partition stops: a thousandth of the other side, at
    // most (the truth: 0).
    const Scene uncut = dividedBox();
    Scene cut = uncut;
    const size_t geometry = cut.polygons.size() - 1;  // the lamp last: left out
    std::vector<Polygon> lamp(cut.polygons.begin() + static_cast<long>(geometry),
                              cut.polygons.end());
    cut.polygons.resize(geometry);
    const ContactSplitReport r = splitAtContacts(cut.polygons, geometry);
    EXPECT_EQ(r.polygonsCut, 4);  // floor, ceiling, both long walls
    cut.lights[0].polygons = {static_cast<int>(cut.polygons.size())};
    cut.polygons.insert(cut.polygons.end(), lamp.begin(), lamp.end());
    const double leakUncut = closedOffShare(uncut);
    const double leakCut = closedOffShare(cut);
    std::printf("closed-off share: uncut %.3g, cut %.3g\n", leakUncut, leakCut);
    EXPECT_GT(leakUncut, 0.01);
    EXPECT_LT(leakCut, 1e-3);
}
