// Shaft (Haines & Wallace 1991): conservativeness against sampled convex hulls, culling in
// the cases where the answer is known, and the degenerate boxes radiosity produces (flat
// bounds of axis-aligned polygons, identical and overlapping boxes).
#include "radiosity/detail/shaft.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace radiosity;

namespace {

Bounds3 box(Vec3 lo, Vec3 hi) {
    Bounds3 b;
    b.lo = lo;
    b.hi = hi;
    return b;
}

Vec3 corner(const Bounds3& b, int k) {
    return {k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z};
}

// Random point of the convex hull of a and b: a random convex combination of 4 random
// corners of a and 4 of b. Hull vertices are box corners, so every hull point is such a
// combination; weights drawn as w^4 push samples onto the hull's faces and edges, where
// rounding matters.
Vec3 hullPoint(const Bounds3& a, const Bounds3& b, std::mt19937& rng) {
    std::uniform_int_distribution<int> pick(0, 7);
    std::uniform_real_distribution<double> u(0, 1);
    Vec3 p{0, 0, 0};
    double total = 0;
    for (int k = 0; k < 8; ++k) {
        const double w = std::pow(u(rng), 4);
        p += w * corner(k < 4 ? a : b, pick(rng));
        total += w;
    }
    return total > 0 ? p / total : corner(a, 0);
}

// Random box, with probability 1/4 flat on one axis (bounds of an axis-aligned polygon).
Bounds3 randomBox(std::mt19937& rng, double range, double maxSize) {
    std::uniform_real_distribution<double> pos(-range, range);
    std::uniform_real_distribution<double> size(0, maxSize);
    std::uniform_int_distribution<int> flat(0, 11);
    Vec3 lo{pos(rng), pos(rng), pos(rng)};
    Vec3 d{size(rng), size(rng), size(rng)};
    const int f = flat(rng);
    if (f < 3) d[f] = 0;
    return box(lo, lo + d);
}

}  // namespace

TEST(Shaft, AlignedBoxesNeedNoPlanesAndCullOffAxis) {
    // Two unit boxes at x = 0 and x = 10, aligned: the shaft is their union box.
    const Shaft s(box({0, 0, 0}, {1, 1, 1}), box({10, 0, 0}, {11, 1, 1}));
    EXPECT_EQ(s.planeCount(), 0);
    EXPECT_EQ(s.bounds().lo, Vec3(0, 0, 0));
    EXPECT_EQ(s.bounds().hi, Vec3(11, 1, 1));
    EXPECT_FALSE(s.mayIntersect(box({5, 5, 0}, {6, 6, 1})));     // beside the shaft
    EXPECT_TRUE(s.mayIntersect(box({5, 0, 0}, {6, 1, 1})));      // in the middle of it
    EXPECT_TRUE(s.mayIntersect(box({5, 0.9, 0.9}, {6, 3, 3})));  // overlapping a corner
    EXPECT_FALSE(s.mayIntersect(box({12, 0, 0}, {13, 1, 1})));   // beyond B
}

TEST(Shaft, DiagonalBoxesCullTheCornerWedges) {
    // A at the origin, B up the x = y diagonal: the union box has two empty wedges (near
    // (11, 0) and (0, 11)) that the two silhouette planes cut away.
    const Shaft s(box({0, 0, 0}, {1, 1, 1}), box({10, 10, 0}, {11, 11, 1}));
    EXPECT_EQ(s.planeCount(), 2);
    EXPECT_FALSE(s.mayIntersect(box({8, 0, 0}, {9, 1, 1})));  // inside union box, off hull
    EXPECT_FALSE(s.mayIntersect(box({0, 8, 0}, {1, 9, 1})));
    EXPECT_TRUE(s.mayIntersect(box({5, 5, 0}, {6, 6, 1})));
    EXPECT_FALSE(s.contains({9, 0.5, 0.5}));
    EXPECT_TRUE(s.contains({5.5, 5.5, 0.5}));
    // The silhouette plane y = x - 1 passes through A's edge (1, 0) and B's (11, 10).
    EXPECT_TRUE(s.contains({6, 5, 0.5}));
    EXPECT_FALSE(s.contains({6, 4.99, 0.5}));
}

TEST(Shaft, RandomPairsContainTheirConvexHull) {
    std::mt19937 rng(12345);
    int maxPlanes = 0;
    for (int pair = 0; pair < 500; ++pair) {
        const Bounds3 a = randomBox(rng, 10, 3);
        const Bounds3 b = randomBox(rng, 10, 3);
        const Shaft s(a, b);
        ASSERT_LE(s.planeCount(), 8);
        maxPlanes = std::max(maxPlanes, s.planeCount());
        for (int k = 0; k < 8; ++k) {
            ASSERT_TRUE(s.contains(corner(a, k))) << "pair " << pair << " corner of A " << k;
            ASSERT_TRUE(s.contains(corner(b, k))) << "pair " << pair << " corner of B " << k;
        }
        for (int i = 0; i < 200; ++i) {
            const Vec3 p = hullPoint(a, b, rng);
            ASSERT_TRUE(s.contains(p)) << "pair " << pair << " sample " << i;
            // A tiny box around a hull point, as an element's bounds would be.
            ASSERT_TRUE(s.mayIntersect(box(p - Vec3(1e-6), p + Vec3(1e-6))));
        }
        EXPECT_TRUE(s.mayIntersect(a));
        EXPECT_TRUE(s.mayIntersect(b));
    }
    EXPECT_GE(maxPlanes, 4);  // the random pairs exercised the planes, not only union boxes
}

TEST(Shaft, CrossedBoxesReachTheMaximumOfEightPlanes) {
    // A is longer on x, B on y and z: every (x, y) and (x, z) corner is a silhouette.
    std::mt19937 rng(8);
    const Bounds3 a = box({0, 4, 4}, {10, 6, 6});
    const Bounds3 b = box({4, 0, 0}, {6, 10, 10});
    const Shaft s(a, b);
    EXPECT_EQ(s.planeCount(), 8);
    for (int i = 0; i < 2000; ++i) ASSERT_TRUE(s.contains(hullPoint(a, b, rng)));
    EXPECT_FALSE(s.contains({0.5, 0.5, 5}));  // union-box corner far from both boxes
    EXPECT_FALSE(s.mayIntersect(box({0, 0, 0}, {1, 1, 10})));
    EXPECT_TRUE(s.mayIntersect(box({4.5, 4.5, 4.5}, {5.5, 5.5, 5.5})));
}

TEST(Shaft, CulledBoxesHoldNoPointOfTheShaft) {
    // mayIntersect false must mean "entirely outside": no sampled point of a culled box is
    // inside the shaft, and no hull point lies in a culled box.
    std::mt19937 rng(777);
    std::uniform_real_distribution<double> u(0, 1);
    int culled = 0;
    for (int pair = 0; pair < 200; ++pair) {
        const Bounds3 a = randomBox(rng, 5, 2);
        const Bounds3 b = randomBox(rng, 5, 2);
        const Shaft s(a, b);
        std::vector<Vec3> hull;
        for (int i = 0; i < 300; ++i) hull.push_back(hullPoint(a, b, rng));
        for (int q = 0; q < 50; ++q) {
            const Bounds3 query = randomBox(rng, 6, 1.5);
            if (s.mayIntersect(query)) continue;
            ++culled;
            for (int i = 0; i < 64; ++i) {
                const Vec3 p = query.lo + Vec3(u(rng), u(rng), u(rng)) * query.diagonal();
                ASSERT_FALSE(s.contains(p)) << "pair " << pair << " query " << q;
            }
            for (const Vec3& p : hull) {
                const bool inside = p.x >= query.lo.x && p.x <= query.hi.x && p.y >= query.lo.y &&
                                    p.y <= query.hi.y && p.z >= query.lo.z && p.z <= query.hi.z;
                ASSERT_FALSE(inside) << "pair " << pair << " query " << q;
            }
        }
    }
    EXPECT_GT(culled, 1000);  // the test exercised culling, not only acceptance
}

TEST(Shaft, FlatBoxesOfAxisAlignedPolygons) {
    std::mt19937 rng(99);
    // Floor patch (z = 0) and a smaller ceiling patch (z = 2.5) offset in x and y.
    {
        const Bounds3 floor = box({0, 0, 0}, {1, 1, 0});
        const Bounds3 ceiling = box({3, 0.2, 2.5}, {4, 0.5, 2.5});
        const Shaft s(floor, ceiling);
        for (int i = 0; i < 2000; ++i) ASSERT_TRUE(s.contains(hullPoint(floor, ceiling, rng)));
        EXPECT_FALSE(s.mayIntersect(box({0, 0, 2}, {0.5, 1, 2.4})));   // above the floor patch
        EXPECT_FALSE(s.mayIntersect(box({3, 0, 0}, {4, 1, 0.5})));     // below the ceiling one
        EXPECT_TRUE(s.mayIntersect(box({1.5, 0, 1}, {2.5, 1, 1.5})));  // between them
    }
    // Floor patch and a wall patch (x = 5) meeting at right angles.
    {
        const Bounds3 floor = box({0, 0, 0}, {1, 1, 0});
        const Bounds3 wall = box({5, 0, 1}, {5, 1, 2});
        const Shaft s(floor, wall);
        for (int i = 0; i < 2000; ++i) ASSERT_TRUE(s.contains(hullPoint(floor, wall, rng)));
        EXPECT_FALSE(s.mayIntersect(box({4, 0, 0}, {4.5, 1, 0.3})));  // corner wedge
        EXPECT_FALSE(s.mayIntersect(box({0, 0, 1.5}, {0.5, 1, 2})));  // other wedge
    }
    // Two patches in one plane: the shaft is flat too.
    {
        const Bounds3 p = box({0, 0, 0}, {1, 1, 0});
        const Bounds3 q = box({3, 2, 0}, {4, 3, 0});
        const Shaft s(p, q);
        EXPECT_EQ(s.bounds().diagonal().z, 0);
        for (int i = 0; i < 2000; ++i) ASSERT_TRUE(s.contains(hullPoint(p, q, rng)));
        EXPECT_TRUE(s.mayIntersect(box({2, 1.2, -1}, {2.1, 1.3, 1})));     // pierces the plane
        EXPECT_FALSE(s.mayIntersect(box({2, 1.2, 0.01}, {2.1, 1.3, 1})));  // just above it
        EXPECT_FALSE(s.mayIntersect(box({3, 0, -1}, {4, 1, 1})));          // in the wedge
    }
}

TEST(Shaft, IdenticalBoxesGiveTheBoxItself) {
    const Bounds3 a = box({1, 2, 3}, {2, 4, 3.5});
    const Shaft s(a, a);
    EXPECT_EQ(s.planeCount(), 0);
    EXPECT_EQ(s.bounds().lo, a.lo);
    EXPECT_EQ(s.bounds().hi, a.hi);
    for (int k = 0; k < 8; ++k) EXPECT_TRUE(s.contains(corner(a, k)));
    EXPECT_TRUE(s.mayIntersect(a));
    EXPECT_FALSE(s.mayIntersect(box({2.1, 2, 3}, {3, 4, 3.5})));
    EXPECT_FALSE(s.contains({1.5, 3, 3.6}));
}

TEST(Shaft, OverlappingAndNestedBoxes) {
    std::mt19937 rng(5);
    // Cubes offset along (1, 1, 1): A reaches farther on every min side, B on every max
    // side, so each axis pair has 2 silhouette corners: 6 planes.
    const Bounds3 a = box({0, 0, 0}, {2, 2, 2});
    const Bounds3 b = box({1, 1, 1}, {3, 3, 3});
    const Shaft s(a, b);
    EXPECT_EQ(s.planeCount(), 6);
    for (int i = 0; i < 2000; ++i) ASSERT_TRUE(s.contains(hullPoint(a, b, rng)));
    EXPECT_FALSE(s.contains({2.9, 0.1, 1.5}));  // in the union box's (x max, y min) wedge
    EXPECT_FALSE(s.mayIntersect(box({2.8, 0, 1}, {3, 0.2, 2})));
    EXPECT_TRUE(s.mayIntersect(box({1.9, 1.9, 1.9}, {2.1, 2.1, 2.1})));

    // One box inside the other: the shaft is the outer box, no planes.
    const Bounds3 outer = box({0, 0, 0}, {4, 4, 4});
    const Shaft nested(outer, box({1, 1, 1}, {2, 2, 2}));
    EXPECT_EQ(nested.planeCount(), 0);
    EXPECT_EQ(nested.bounds().hi, outer.hi);
    EXPECT_TRUE(nested.mayIntersect(box({3.5, 3.5, 3.5}, {5, 5, 5})));
}

TEST(Shaft, EmptyBoxLeavesTheOther) {
    const Bounds3 a = box({0, 0, 0}, {1, 1, 1});
    const Shaft s(Bounds3{}, a);
    EXPECT_EQ(s.planeCount(), 0);
    EXPECT_TRUE(s.contains({0.5, 0.5, 0.5}));
    EXPECT_FALSE(s.contains({1.5, 0.5, 0.5}));
    EXPECT_FALSE(s.mayIntersect(Bounds3{}));
    const Shaft none(Bounds3{}, Bounds3{});
    EXPECT_FALSE(none.mayIntersect(a));
    EXPECT_FALSE(none.contains({0, 0, 0}));
}
