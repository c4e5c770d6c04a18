// Visibility (Embree 3): blocked and clear segments, end points on polygons, triangles as
// degenerate quads, batch = singles, first hits, the ray counter, and concurrent use.
#include "radiosity/visibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

#include "radiosity/detail/rng.h"

using namespace radiosity;

namespace {

void addPolygon(Scene& scene, const std::vector<Vec3>& corners) {
    ASSERT_EQ(checkPolygon(corners).status, PolygonCheck::Status::ok);
    scene.polygons.push_back(makePolygon(corners, 0, Rgb::gray(0.5)));
}

// Axis-aligned unit square at height z, facing up (+z) or down.
void addSquareZ(Scene& scene, double x0, double y0, double size, double z, bool up) {
    const Vec3 a{x0, y0, z}, b{x0 + size, y0, z}, c{x0 + size, y0 + size, z}, d{x0, y0 + size, z};
    if (up)
        addPolygon(scene, {a, b, c, d});
    else
        addPolygon(scene, {a, d, c, b});
}

Scene baseScene() {
    Scene scene;
    scene.objects.push_back("test");
    return scene;
}

// A closed 4 x 3 x 2.5 m room (6 quads, facing in) offset far from the origin so that float
// rounding of coordinates is realistic, plus a table top, a triangle and a lamp: ~10 polygons.
Scene roomScene(Vec3 o) {
    Scene s = baseScene();
    const double X = 4, Y = 3, Z = 2.5;
    auto p = [&](double x, double y, double z) { return o + Vec3{x, y, z}; };
    addPolygon(s, {p(0, 0, 0), p(X, 0, 0), p(X, Y, 0), p(0, Y, 0)});              // floor, up
    addPolygon(s, {p(0, 0, Z), p(0, Y, Z), p(X, Y, Z), p(X, 0, Z)});              // ceiling, down
    addPolygon(s, {p(0, 0, 0), p(0, 0, Z), p(X, 0, Z), p(X, 0, 0)});              // wall y = 0, +y
    addPolygon(s, {p(0, Y, 0), p(X, Y, 0), p(X, Y, Z), p(0, Y, Z)});              // wall y = Y, -y
    addPolygon(s, {p(0, 0, 0), p(0, Y, 0), p(0, Y, Z), p(0, 0, Z)});              // wall x = 0, +x
    addPolygon(s, {p(X, 0, 0), p(X, 0, Z), p(X, Y, Z), p(X, Y, 0)});              // wall x = X, -x
    addPolygon(s, {p(1, 1, 0.8), p(2.5, 1, 0.8), p(2.5, 2, 0.8), p(1, 2, 0.8)});  // table
    addPolygon(s, {p(3, 0.5, 0.1), p(3.5, 0.5, 0.1), p(3, 0.5, 1.5)});            // triangle board
    addPolygon(s, {p(1.5, 1.2, 2.3), p(1.5, 1.6, 2.3), p(2, 1.6, 2.3), p(2, 1.2, 2.3)});  // lamp
    s.polygons.back().light = 0;
    s.lights.push_back({"lamp", {8}, Rgb::gray(10)});
    return s;
}

// Random point on polygon p of the scene (uniform in the parallelogram / triangle).
Vec3 pointOn(const Polygon& p, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    double s = u(rng), t = u(rng);
    if (p.vertexCount == 3) {
        if (s + t > 1) {
            s = 1 - s;
            t = 1 - t;
        }
        return p.v[0] + s * (p.v[1] - p.v[0]) + t * (p.v[2] - p.v[0]);
    }
    // Bilinear; exact for the axis-aligned rectangles used here.
    return (1 - s) * (1 - t) * p.v[0] + s * (1 - t) * p.v[1] + s * t * p.v[2] +
           (1 - s) * t * p.v[3];
}

}  // namespace

TEST(Visibility, SquareBetweenPointsBlocksAndBesideDoesNot) {
    Scene s = baseScene();
    addSquareZ(s, 0, 0, 1, 0, true);
    const Visibility vis(s);
    EXPECT_FALSE(vis.visible({0.5, 0.5, -1}, {0.5, 0.5, 1}));
    EXPECT_FALSE(vis.visible({0.5, 0.5, 1}, {0.5, 0.5, -1}));          // back side occludes too
    EXPECT_FALSE(vis.visible({0.01, 0.99, -0.1}, {0.98, 0.02, 0.3}));  // oblique
    EXPECT_TRUE(vis.visible({2, 0.5, -1}, {2, 0.5, 1}));               // beside
    EXPECT_TRUE(vis.visible({1.01, 0.5, -1}, {1.01, 0.5, 1}));         // just beside the edge
    EXPECT_TRUE(vis.visible({0.5, 0.5, 0.5}, {0.5, 0.5, 2}));          // segment ends above it
    EXPECT_TRUE(vis.visible({0.5, 0.5, 1}, {0.5, 0.5, 1}));            // zero length
}

TEST(Visibility, EndPointsOnPolygonsDoNotBlockThemselves) {
    // Floor (z = 0, up) and ceiling (z = 1, down): nothing between them.
    Scene s = baseScene();
    addSquareZ(s, 0, 0, 1, 0, true);
    addSquareZ(s, 0, 0, 1, 1, false);
    const Visibility vis(s);
    EXPECT_TRUE(vis.visible({0.5, 0.5, 0}, {0.5, 0.5, 1}));
    EXPECT_TRUE(vis.visible({0.5, 0.5, 1}, {0.5, 0.5, 0}));
    std::mt19937 rng(3);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 a = pointOn(s.polygons[0], rng), b = pointOn(s.polygons[1], rng);
        ASSERT_TRUE(vis.visible(a, b)) << i;
    }
}

TEST(Visibility, EndPointsOnRoomSurfacesFarFromTheOrigin) {
    // Between points on different faces of a closed room 40 m from the origin (float
    // spacing there ~4 um), only the table, triangle and lamp may block: segments between
    // two walls that pass above the furniture's height range must all be clear, also at
    // grazing angles along the floor.
    const Vec3 o{37.3, -12.1, 3.7};
    const Scene s = roomScene(o);
    const Visibility vis(s);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 2000; ++i) {
        // Upper band of wall y = 0 to upper band of wall y = Y (above the lamp at 2.3 m).
        const Vec3 a = o + Vec3{4 * u(rng), 0, 2.31 + 0.19 * u(rng)};
        const Vec3 b = o + Vec3{4 * u(rng), 3, 2.31 + 0.19 * u(rng)};
        ASSERT_TRUE(vis.visible(a, b)) << i;
        // Floor to floor: the segment lies in the floor's plane.
        const Vec3 c = o + Vec3{4 * u(rng), 3 * u(rng), 0};
        const Vec3 d = o + Vec3{0.5 + 0.4 * u(rng), 3 * u(rng), 0};  // away from the board
        ASSERT_TRUE(vis.visible(c, d)) << i;
        // Floor corner region to the wall x = 0 it meets.
        const Vec3 e = o + Vec3{0.3 * u(rng), 3 * u(rng), 0};
        const Vec3 f = o + Vec3{0, 3 * u(rng), 0.7 * u(rng)};
        ASSERT_TRUE(vis.visible(e, f)) << i;
    }
    // Floor under the table to the lamp: blocked by the table top.
    EXPECT_FALSE(vis.visible(o + Vec3{1.75, 1.4, 0}, o + Vec3{1.75, 1.4, 2.3}));
    // Ceiling to floor beside the table: clear.
    EXPECT_TRUE(vis.visible(o + Vec3{0.5, 0.5, 2.5}, o + Vec3{0.5, 0.5, 0}));
}

TEST(Visibility, EndPolygonIdsMakeGrazingSegmentsExact) {
    // A floor and a wall meeting at a corner, rotated 30 degrees about z so that points on
    // the wall do not round like its vertices. Segments from the floor near the corner to
    // the wall meet the wall at grazing angles down to ~1e-6 rad: with the end polygons
    // named, none may self-block.
    const double c = std::cos(0.5236), s = std::sin(0.5236);
    const Vec3 o{1.7, -0.4, 0.3};
    auto P = [&](double x, double y, double z) {
        return o + Vec3{c * x - s * y, s * x + c * y, z};
    };
    Scene scene = baseScene();
    addPolygon(scene, {P(0, 0, 0), P(4, 0, 0), P(4, 3, 0), P(0, 3, 0)});              // floor, 0
    addPolygon(scene, {P(0, 0, 0), P(0, 3, 0), P(0, 3, 2.5), P(0, 0, 2.5)});          // wall, 1
    addPolygon(scene, {P(2, 1, 0.2), P(2, 1.5, 0.2), P(2, 1.5, 0.7), P(2, 1, 0.7)});  // 2
    const Visibility vis(scene);
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> from, to;
    for (int i = 0; i < 5000; ++i) {
        from.push_back(P(std::pow(10.0, -6 + 6 * u(rng)) * 0.5, 3 * u(rng), 0));  // x < 0.5
        to.push_back(P(0, 3 * u(rng), 2.5 * u(rng)));
        ASSERT_TRUE(vis.visible(from.back(), to.back(), 0, 1)) << i;
        ASSERT_TRUE(vis.visible(to.back(), from.back(), 1, 0)) << i;
    }
    const auto out = std::make_unique<bool[]>(from.size());
    const int n = static_cast<int>(from.size());
    EXPECT_EQ(vis.visibleBatch(from.data(), to.data(), n, out.get(), 0, 1), n);
    // Naming the end polygons does not hide other blockers: the panel at x = 2 still
    // blocks, unless it is named itself.
    const Vec3 a = P(3, 1.25, 0), b = P(0, 1.25, 0.9);
    EXPECT_FALSE(vis.visible(a, b, 0, 1));
    EXPECT_TRUE(vis.visible(a, b, 0, 2));
    EXPECT_FALSE(vis.visibleBatch(&a, &b, 1, nullptr, 0, 1));
    EXPECT_TRUE(vis.visibleBatch(&a, &b, 1, nullptr, 2, -1));
}

TEST(Visibility, EmittingFacesOcclude) {
    Scene s = baseScene();
    addSquareZ(s, 0, 0, 1, 2, false);
    s.polygons[0].light = 0;
    s.polygons[0].rho = Rgb{};
    s.lights.push_back({"panel", {0}, Rgb::gray(5)});
    const Visibility vis(s);
    EXPECT_FALSE(vis.visible({0.5, 0.5, 1}, {0.5, 0.5, 3}));
}

TEST(Visibility, TriangleBlocksOnlyInsideItsArea) {
    // Triangle (0,0) (1,0) (0,1) at z = 0, stored as a quad with v3 = v2: the half x + y > 1
    // of its bounding square must stay clear.
    Scene s = baseScene();
    addPolygon(s, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    ASSERT_EQ(s.polygons[0].vertexCount, 3);
    const Visibility vis(s);
    auto through = [&](double x, double y) { return vis.visible({x, y, -1}, {x, y, 1}); };
    EXPECT_FALSE(through(0.2, 0.2));
    EXPECT_FALSE(through(0.6, 0.3));   // x + y = 0.9
    EXPECT_FALSE(through(0.05, 0.9));  // x + y = 0.95
    EXPECT_TRUE(through(0.6, 0.45));   // x + y = 1.05
    EXPECT_TRUE(through(0.8, 0.8));
    EXPECT_TRUE(through(0.95, 0.95));
    EXPECT_TRUE(through(-0.1, 0.5));
    const Visibility::Hit hit = vis.intersect({0.9, 0.9, 1}, {0, 0, -1});
    EXPECT_EQ(hit.polygon, -1);
}

TEST(Visibility, BatchEqualsSingles) {
    const Scene s = roomScene({1, 2, 0});
    const Visibility vis(s);
    std::mt19937 rng(21);
    // n not a multiple of 16, with some zero-length segments and end points on polygons.
    const int n = 1003;
    std::vector<Vec3> from(n), to(n);
    std::uniform_int_distribution<int> pick(0, static_cast<int>(s.polygons.size()) - 1);
    for (int i = 0; i < n; ++i) {
        from[i] = pointOn(s.polygons[pick(rng)], rng);
        to[i] = i % 97 == 0 ? from[i] : pointOn(s.polygons[pick(rng)], rng);
    }
    const auto out = std::make_unique<bool[]>(n);  // vector<bool> has no bool* storage
    const int count = vis.visibleBatch(from.data(), to.data(), n, out.get());
    int singles = 0, blocked = 0;
    for (int i = 0; i < n; ++i) {
        const bool v = vis.visible(from[i], to[i]);
        ASSERT_EQ(out[i], v) << i;
        singles += v ? 1 : 0;
        blocked += v ? 0 : 1;
    }
    EXPECT_EQ(count, singles);
    EXPECT_GT(blocked, 10);  // the scene did block some segments
    EXPECT_EQ(vis.visibleBatch(from.data(), to.data(), n), count);  // out may be null
    EXPECT_EQ(vis.visibleBatch(from.data(), to.data(), 0), 0);
}

TEST(Visibility, IntersectReturnsPolygonAndDistance) {
    Scene s = baseScene();
    addSquareZ(s, 0, 0, 1, 1, false);  // polygon 0 at z = 1
    addSquareZ(s, 0, 0, 1, 3, false);  // polygon 1 at z = 3
    const Visibility vis(s);
    Visibility::Hit hit = vis.intersect({0.5, 0.5, 0}, {0, 0, 1});
    EXPECT_EQ(hit.polygon, 0);
    EXPECT_NEAR(hit.t, 1.0, 1e-6);  // float ray: ~1e-7 relative
    hit = vis.intersect({0.5, 0.5, 0}, {0, 0, 1}, 1.5);
    EXPECT_EQ(hit.polygon, 1);
    EXPECT_NEAR(hit.t, 3.0, 1e-6);
    EXPECT_EQ(vis.intersect({0.5, 0.5, 0}, {0, 0, 1}, 0, 0.5).polygon, -1);
    EXPECT_EQ(vis.intersect({0.5, 0.5, 0}, {0, 0, -1}).polygon, -1);
    EXPECT_EQ(vis.intersect({0.5, 0.5, 4}, {0, 0, -1}).polygon, 1);
    // Oblique unit direction: t is the distance.
    const Vec3 dir = glm::normalize(Vec3{0.3, 0.1, 1});
    hit = vis.intersect({0.2, 0.2, 0}, dir);
    EXPECT_EQ(hit.polygon, 0);
    EXPECT_NEAR(hit.t, 1.0 / dir.z, 1e-6);
}

TEST(Visibility, RaysCounterCountsOcclusionQueries) {
    const Scene s = roomScene({0, 0, 0});
    const Visibility vis(s);
    EXPECT_EQ(vis.raysCast(), 0u);
    vis.visible({1, 1, 1}, {2, 2, 2});
    EXPECT_EQ(vis.raysCast(), 1u);
    std::vector<Vec3> a(37, Vec3{0.5, 0.5, 0.5}), b(37, Vec3{3.5, 2.5, 2});
    vis.visibleBatch(a.data(), b.data(), 37);
    EXPECT_EQ(vis.raysCast(), 38u);
    vis.intersect({1, 1, 1}, {0, 0, 1});
    EXPECT_EQ(vis.raysCast(), 38u);  // first-hit rays are not occlusion rays
    EXPECT_STREQ(Visibility::kRaysCounterName, "Visibility/Rays");
}

TEST(Visibility, EmptySceneBlocksNothing) {
    const Scene s = baseScene();
    const Visibility vis(s);
    EXPECT_TRUE(vis.visible({0, 0, 0}, {1, 1, 1}));
    Vec3 a{0, 0, 0}, b{1, 0, 0};
    EXPECT_EQ(vis.visibleBatch(&a, &b, 1), 1);
    EXPECT_EQ(vis.intersect({0, 0, 0}, {1, 0, 0}).polygon, -1);
}

TEST(Visibility, RejectsPolygonsWithoutThreeOrFourVertices) {
    Scene s = baseScene();
    addSquareZ(s, 0, 0, 1, 0, true);
    s.polygons.push_back(Polygon{});  // vertexCount 0: not made by makePolygon
    EXPECT_THROW(Visibility{s}, std::invalid_argument);
}

TEST(Visibility, ConcurrentCallsGiveTheSameResults) {
    const Scene s = roomScene({-5, 3, 1});
    const Visibility vis(s);
    std::mt19937 rng(4);
    const int n = 4000;
    std::vector<Vec3> from(n), to(n);
    std::uniform_int_distribution<int> pick(0, static_cast<int>(s.polygons.size()) - 1);
    for (int i = 0; i < n; ++i) {
        from[i] = pointOn(s.polygons[pick(rng)], rng);
        to[i] = pointOn(s.polygons[pick(rng)], rng);
    }
    std::vector<char> reference(n);
    for (int i = 0; i < n; ++i) reference[i] = vis.visible(from[i], to[i]);
    const uint64_t before = vis.raysCast();

    // Each thread: singles, a batch, and first hits, compared after joining.
    struct Result {
        std::vector<char> singles, batch;
        std::vector<int> hits;
    };
    std::vector<Result> results(2);
    auto work = [&](Result& r) {
        r.singles.resize(n);
        r.batch.resize(n);
        for (int i = 0; i < n; ++i) r.singles[i] = vis.visible(from[i], to[i]);
        const auto batch = std::make_unique<bool[]>(n);
        vis.visibleBatch(from.data(), to.data(), n, batch.get());
        for (int i = 0; i < n; ++i) r.batch[i] = batch[i];
        for (int i = 0; i < n; ++i)
            r.hits.push_back(vis.intersect(from[i], glm::normalize(to[i] - from[i]), 1e-3).polygon);
    };
    std::thread t0(work, std::ref(results[0]));
    std::thread t1(work, std::ref(results[1]));
    t0.join();
    t1.join();
    for (const Result& r : results) {
        EXPECT_EQ(r.singles, reference);
        EXPECT_EQ(r.batch, reference);
        EXPECT_EQ(r.hits, results[0].hits);
    }
    EXPECT_EQ(vis.raysCast(), before + 2 * 2 * static_cast<uint64_t>(n));
}

TEST(Visibility, AddedPolygonsBlockMoveAndGoAway) {
    Scene scene = baseScene();
    addSquareZ(scene, -5, -5, 10, 0, true);  // a floor, polygon 0
    Visibility vis(scene);
    const Vec3 a{0.5, 0.5, 0.1}, b{0.5, 0.5, 3};
    ASSERT_TRUE(vis.visible(a, b));
    // A square at z = 1 over the segment, as polygon 1 of the scene.
    Scene extra = baseScene();
    addSquareZ(extra, 0, 0, 1, 1, true);
    const int group = vis.addPolygons(extra.polygons, 1);
    EXPECT_FALSE(vis.visible(a, b));
    // Hits report the added polygon's scene index, and end filters use it.
    const Visibility::Hit hit = vis.intersect(a, {0, 0, 1});
    EXPECT_EQ(hit.polygon, 1);
    EXPECT_NEAR(hit.t, 0.9, 1e-6);
    EXPECT_TRUE(vis.visible({0.5, 0.5, 1}, b, 1));
    // Moved aside, it no longer blocks; moved back, it does.
    Scene moved = baseScene();
    addSquareZ(moved, 3, 3, 1, 1, true);
    vis.movePolygons(group, moved.polygons);
    EXPECT_TRUE(vis.visible(a, b));
    EXPECT_FALSE(vis.visible({3.5, 3.5, 0.1}, {3.5, 3.5, 3}));
    vis.removePolygons(group);
    EXPECT_TRUE(vis.visible({3.5, 3.5, 0.1}, {3.5, 3.5, 3}));
    EXPECT_THROW(vis.removePolygons(group), std::invalid_argument);
    Scene two = baseScene();
    addSquareZ(two, 0, 0, 1, 1, true);
    addSquareZ(two, 0, 0, 1, 2, true);
    EXPECT_THROW(vis.movePolygons(vis.addPolygons(extra.polygons, 1), two.polygons),
                 std::invalid_argument);
}

TEST(Visibility, HiddenScenePolygonsNeitherBlockNorAreHitUntilShown) {
    // Real-object removal: a blocker of the scene itself (geometry 0) is hidden and shown.
    Scene scene = baseScene();
    addSquareZ(scene, -5, -5, 10, 0, true);  // floor, polygon 0
    addSquareZ(scene, 0, 0, 1, 1, true);     // blocker, polygon 1
    addSquareZ(scene, 0, 0, 1, 2, false);    // ceiling over it, polygon 2
    Visibility vis(scene);
    const Vec3 a{0.5, 0.5, 0.1}, b{0.5, 0.5, 1.9};
    ASSERT_FALSE(vis.visible(a, b));
    const std::vector<int> blocker{1};
    vis.hidePolygons(blocker);
    EXPECT_TRUE(vis.hidden(1));
    EXPECT_FALSE(vis.hidden(0));
    EXPECT_TRUE(vis.visible(a, b));
    // Rays through every part of the hidden square, its edges and corners included, go on
    // to the ceiling: the collapsed quad is hit nowhere.
    for (double x : {0.0, 1e-4, 0.25, 0.5, 0.9999, 1.0})
        for (double y : {0.0, 1e-4, 0.5, 1.0}) {
            const Visibility::Hit hit = vis.intersect({x, y, 0.1}, {0, 0, 1});
            EXPECT_EQ(hit.polygon, 2) << x << " " << y;
        }
    bool batch[2] = {false, false};
    const Vec3 from[2] = {a, {0.2, 0.8, 0.1}}, to[2] = {b, {0.3, 0.7, 1.9}};
    EXPECT_EQ(vis.visibleBatch(from, to, 2, batch), 2);
    vis.hidePolygons(blocker);  // twice: nothing more
    vis.showPolygons(blocker);
    EXPECT_FALSE(vis.hidden(1));
    EXPECT_FALSE(vis.visible(a, b));
    const Visibility::Hit back = vis.intersect({0.5, 0.5, 0.1}, {0, 0, 1});
    EXPECT_EQ(back.polygon, 1);
    EXPECT_NEAR(back.t, 0.9, 1e-6);
    const std::vector<int> outside{3};
    EXPECT_THROW(vis.hidePolygons(outside), std::invalid_argument);
}

TEST(Visibility, IntersectFrontFindsTheFrontOfASheetModelledAsTwoFaces) {
    // A thin part as a mesh exporter writes it: the same triangles twice, reversed, at the
    // very same place. Whichever of the two Embree reports first, a ray from either side
    // must get the face that looks at it; a plain one-sided face seen from behind stays a
    // back face (a hole would be wrong for a sheet, but right for a single face's back).
    Scene s;
    s.objects = {"sheet", "single"};
    const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{1, 1, 0}, d{0, 1, 0};
    s.polygons.push_back(makePolygon({a, b, c, d}, 0, Rgb::gray(0.5)));  // faces +z
    s.polygons.push_back(makePolygon({a, d, c, b}, 0, Rgb::gray(0.5)));  // faces -z
    const Vec3 off{3, 0, 0};
    s.polygons.push_back(makePolygon({a + off, b + off, c + off, d + off}, 1, Rgb::gray(0.5)));
    const Visibility vis(s);
    Rng rng(11);
    for (int i = 0; i < 200; ++i) {
        const double x = 0.05 + 0.9 * rng.uniform(), y = 0.05 + 0.9 * rng.uniform();
        const FrontHit down = intersectFront(vis, s, {x, y, 2}, {0, 0, -1});
        ASSERT_TRUE(down.front) << i;
        EXPECT_EQ(down.hit.polygon, 0) << i;
        EXPECT_NEAR(down.hit.t, 2.0, 1e-6) << i;
        const FrontHit up = intersectFront(vis, s, {x, y, -2}, {0, 0, 1});
        ASSERT_TRUE(up.front) << i;
        EXPECT_EQ(up.hit.polygon, 1) << i;
        const FrontHit back = intersectFront(vis, s, Vec3{x, y, -2} + off, {0, 0, 1});
        EXPECT_FALSE(back.front) << i;
        EXPECT_EQ(back.hit.polygon, 2) << i;
    }
}
