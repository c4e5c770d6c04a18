// Stress rooms (tests/support/stress_room.h): the generator's own guarantees (valid
// polygons, closed room, no overlaps, lamps 5 mm from walls, reproducible seeds), then
// the solver on five of them (finishes, conserves energy, finite, thread-independent).
#include "tests/support/stress_room.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "radiosity/solver.h"
#include "radiosity/visibility.h"

using namespace radiosity;
using stress::LampMount;
using stress::LocalBox;
using stress::makeStressRoom;
using stress::StressRoom;
using stress::StressRoomOptions;

namespace {

/// The seeds the generator tests sweep: stressOptionsForSeed mixes quads and triangles
/// (grid 1-3), jitter, scales from 2 mm to 20, rotations and offsets.
constexpr int kSweepSeeds = 40;

StressRoom sweepRoom(int seed) {
    return makeStressRoom(stress::stressOptionsForSeed(seed));
}

/// FNV-1a over the bytes of every vertex, reflectance and radiance: equal hashes mean
/// the same room bit for bit.
uint64_t roomHash(const Scene& s) {
    uint64_t h = 0xcbf29ce484222325ull;
    auto mix = [&h](double x) {
        unsigned char b[sizeof x];
        std::memcpy(b, &x, sizeof x);
        for (unsigned char c : b) h = (h ^ c) * 0x100000001b3ull;
    };
    for (const Polygon& p : s.polygons) {
        for (int i = 0; i < p.vertexCount; ++i) mix(p.v[i].x), mix(p.v[i].y), mix(p.v[i].z);
        mix(p.rho.r), mix(p.rho.g), mix(p.rho.b), mix(p.object), mix(p.light);
    }
    for (const Light& l : s.lights) mix(l.radiance.r), mix(l.radiance.g), mix(l.radiance.b);
    return h;
}

/// Local bounding box of an object's polygons.
LocalBox objectBox(const StressRoom& room, int object) {
    LocalBox b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
    for (const Polygon& p : room.scene.polygons) {
        if (p.object != object) continue;
        for (int i = 0; i < p.vertexCount; ++i) {
            const Vec3 l = room.toLocal(p.v[i]);
            b.lo = glm::min(b.lo, l);
            b.hi = glm::max(b.hi, l);
        }
    }
    return b;
}

/// splitmix64 for the tests' own random points and directions.
struct TestRandom {
    uint64_t s;
    double uniform() {
        uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
    }
    Vec3 direction() {
        for (;;) {
            const Vec3 d{2 * uniform() - 1, 2 * uniform() - 1, 2 * uniform() - 1};
            const double n2 = glm::dot(d, d);
            if (n2 <= 1 && n2 > 1e-4) return d / std::sqrt(n2);
        }
    }
};

bool insideBox(const Vec3& p, const LocalBox& b) {
    return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y && p.z >= b.lo.z &&
           p.z <= b.hi.z;
}

}  // namespace

// ---- the generator -----------------------------------------------------------------------

TEST(StressRoom, EveryPolygonPassesCheckPolygon) {
    for (int seed = 1; seed <= kSweepSeeds; ++seed) {
        const StressRoom room = sweepRoom(seed);
        for (size_t i = 0; i < room.scene.polygons.size(); ++i) {
            const Polygon& p = room.scene.polygons[i];
            const std::vector<Vec3> corners(p.v.begin(), p.v.begin() + p.vertexCount);
            const PolygonCheck c = checkPolygon(corners);
            ASSERT_EQ(c.status, PolygonCheck::Status::ok)
                << "seed " << seed << " polygon " << i << ": " << c.message;
            ASSERT_GT(p.area, 0.0);
            // Reflectance below maxReflectance (0.95) on every channel; lamps reflect nothing.
            for (int k = 0; k < 3; ++k) {
                ASSERT_GE(p.rho[k], 0.0);
                ASSERT_LT(p.rho[k], room.options.maxReflectance);
                if (p.light >= 0) {
                    ASSERT_EQ(p.rho[k], 0.0);
                }
            }
        }
    }
}

TEST(StressRoom, PolygonCountsFollowTheFurniture) {
    // The room's 6 faces and each solid's 6 faces, one quad or 2 grid^2 triangles each,
    // then one quad per lamp; every object's polygons are contiguous (as an OBJ writes them).
    for (int seed = 1; seed <= kSweepSeeds; ++seed) {
        const StressRoom room = sweepRoom(seed);
        const Scene& s = room.scene;
        const size_t perFace = static_cast<size_t>(room.polygonsPerFace());
        EXPECT_EQ(s.polygons.size(), (6 + 6 * room.solids.size()) * perFace + room.lamps.size())
            << "seed " << seed;
        EXPECT_EQ(s.objects.size(), 6 + room.solids.size() + room.lamps.size());
        std::map<int, size_t> perObject;
        int last = -1;
        for (const Polygon& p : s.polygons) {
            if (p.object != last) {
                ASSERT_EQ(perObject.count(p.object), 0u) << "seed " << seed;
            }
            last = p.object;
            ++perObject[p.object];
        }
        for (int o = 0; o < 6; ++o) EXPECT_EQ(perObject[o], perFace) << s.objects[o];
        for (const stress::Solid& solid : room.solids)
            EXPECT_EQ(perObject[solid.object], 6 * perFace) << s.objects[solid.object];
        ASSERT_EQ(s.lights.size(), room.lamps.size());
        for (const Light& l : s.lights) {
            ASSERT_EQ(l.polygons.size(), 1u);
            EXPECT_EQ(s.polygons[l.polygons[0]].vertexCount, 4) << "lamps stay quads";
        }
    }
    // Known counts: a change here means the generator changed what a seed gives.
    EXPECT_EQ(sweepRoom(1).scene.polygons.size(), 1058u);
}

TEST(StressRoom, SeedsAreReproducible) {
    for (int seed = 1; seed <= 10; ++seed)
        EXPECT_EQ(roomHash(sweepRoom(seed).scene), roomHash(sweepRoom(seed).scene));
    EXPECT_NE(roomHash(sweepRoom(1).scene), roomHash(sweepRoom(2).scene));
    // Pinned: only +, -, *, / and sqrt touch the random numbers, so this holds on every
    // platform; a change means the generator changed what seed 1 gives.
    EXPECT_EQ(roomHash(sweepRoom(1).scene), 9905553517135278093ull);
}

TEST(StressRoom, RoomIsClosedAndFacesPointAtTheAir) {
    // From random points of the room's air, every ray hits something within the room's
    // diagonal, and (lamps aside: a quad seen from behind) what it hits first faces it: the
    // room's faces point inwards, the boxes' outwards, and no crack lets a ray through.
    for (int seed = 1; seed <= kSweepSeeds; seed += 3) {
        const StressRoom room = sweepRoom(seed);
        const Visibility vis(room.scene);
        TestRandom rnd{static_cast<uint64_t>(seed)};
        const double reach = 1.01 * glm::length(room.size) * room.options.scale;
        int rays = 0;
        while (rays < 500) {
            const Vec3 local{rnd.uniform() * room.size.x, rnd.uniform() * room.size.y,
                             rnd.uniform() * room.size.z};
            bool inSolid = false;
            for (const stress::Solid& s : room.solids) inSolid = inSolid || insideBox(local, s.box);
            for (const stress::Lamp& l : room.lamps) inSolid = inSolid || insideBox(local, l.slab);
            if (inSolid) continue;
            const Vec3 dir = rnd.direction();
            const Visibility::Hit hit = vis.intersect(room.toWorld(local), dir, 0, 1e30);
            ASSERT_GE(hit.polygon, 0) << "seed " << seed << ": a ray left the room";
            ASSERT_LE(hit.t, reach) << "seed " << seed;
            const Polygon& p = room.scene.polygons[hit.polygon];
            if (p.light < 0) {
                ASSERT_LT(glm::dot(dir, p.normal), 0.0)
                    << "seed " << seed << ": hit the back of " << room.scene.objects[p.object];
            }
            ++rays;
        }
    }
}

TEST(StressRoom, SolidsTouchButNeverOverlap) {
    // Measured on the output polygons (local frame): every solid's box is the one placed
    // (jitter moves vertices into the solid, never out), lies in the room, and shares no
    // volume with another solid or a lamp's slab. Touching boxes share a plane; after
    // the rotation to the world and back their common coordinate differs by rounding
    // only, hence the 1e-9 room sizes allowed as "touching".
    int contacts = 0;
    for (int seed = 1; seed <= kSweepSeeds; ++seed) {
        const StressRoom room = sweepRoom(seed);
        const double tol = 1e-9 * glm::length(room.size);
        std::vector<LocalBox> boxes;
        for (const stress::Solid& s : room.solids) {
            const LocalBox b = objectBox(room, s.object);
            for (int k = 0; k < 3; ++k) {
                ASSERT_NEAR(b.lo[k], s.box.lo[k], tol) << "seed " << seed;
                ASSERT_NEAR(b.hi[k], s.box.hi[k], tol) << "seed " << seed;
                ASSERT_GE(b.lo[k], -tol);
                ASSERT_LE(b.hi[k], room.size[k] + tol);
            }
            boxes.push_back(b);
        }
        for (const stress::Lamp& l : room.lamps) boxes.push_back(l.slab);
        for (size_t i = 0; i < boxes.size(); ++i)
            for (size_t j = i + 1; j < boxes.size(); ++j) {
                double minExtent = 1e300;
                for (int k = 0; k < 3; ++k)
                    minExtent = std::min(minExtent, std::min(boxes[i].hi[k], boxes[j].hi[k]) -
                                                        std::max(boxes[i].lo[k], boxes[j].lo[k]));
                ASSERT_LE(minExtent, tol)
                    << "seed " << seed << ": boxes " << i << " and " << j << " overlap";
                if (minExtent > -tol) ++contacts;
            }
    }
    // The point of the generator: boxes in contact (stacked, side by side, books, boards).
    EXPECT_GT(contacts, 10 * kSweepSeeds);
}

TEST(StressRoom, WallLampsHangFiveMillimetresFromTheirWall) {
    // Measured by rays: from a lamp's centre towards its mounting surface, the first hit is
    // that surface at the lamp's gap (kLampGap = 5 mm, or 0 for a flush ceiling lamp),
    // times the scale; with jitter the surface is up to `jitter` farther (it moves into
    // the wall). Every room has a lamp whose front sees the room beyond the gap.
    int wallLamps = 0, facingWall = 0;
    for (int seed = 1; seed <= kSweepSeeds; ++seed) {
        const StressRoom room = sweepRoom(seed);
        const Scene& s = room.scene;
        const Visibility vis(s);
        const double scale = room.options.scale;
        bool lightsRoom = false;
        for (const stress::Lamp& lamp : room.lamps) {
            const Polygon& q = s.polygons[s.lights[lamp.light].polygons[0]];
            const Vec3 c = q.centroid();
            const bool facesRoom = lamp.mount != LampMount::wallFacingWall;
            const Vec3 toMount = facesRoom ? -q.normal : q.normal;
            // Start on the lamp: tMin (a tenth of the gap) skips the lamp itself, which Embree's
            // float coordinates put up to ~1e-7 of the room's size from c.
            const double tMin = 0.1 * stress::kLampGap * scale;
            const Visibility::Hit hit = vis.intersect(c, toMount, tMin, 1e30);
            if (lamp.gap == 0) continue;  // flush: the ceiling is in the lamp's plane
            ASSERT_GE(hit.polygon, 0);
            EXPECT_LT(s.polygons[hit.polygon].object, 6)
                << "seed " << seed << ": lamp mounted on "
                << s.objects[s.polygons[hit.polygon].object];
            // Embree traces in float relative to the scene's centre: ~1e-6 of the room's size.
            const double tol = 1e-6 * glm::length(room.size) * scale;
            EXPECT_GE(hit.t, stress::kLampGap * scale - tol) << "seed " << seed;
            EXPECT_LE(hit.t, (stress::kLampGap + room.options.jitter) * scale + tol)
                << "seed " << seed;
            if (lamp.mount == LampMount::wallIntoRoom) ++wallLamps;
            if (lamp.mount == LampMount::wallFacingWall) ++facingWall;
            if (facesRoom) {
                const Visibility::Hit front = vis.intersect(c, q.normal, tMin, 1e30);
                lightsRoom = lightsRoom || front.t > 10 * stress::kLampGap * scale;
            }
        }
        for (const stress::Lamp& lamp : room.lamps)
            if (lamp.mount == LampMount::ceiling && lamp.gap == 0) lightsRoom = true;
        EXPECT_TRUE(lightsRoom) << "seed " << seed << ": no lamp lights the room";
    }
    EXPECT_GT(wallLamps, 5);
    EXPECT_GT(facingWall, 5);
}

TEST(StressRoom, ScaleSpansMillimetresToHundredMetres) {
    StressRoomOptions o;
    o.scale = 0.002;
    const double tiny = glm::length(makeStressRoom(o).scene.bounds().diagonal());
    o.scale = 20;
    const double huge = glm::length(makeStressRoom(o).scene.bounds().diagonal());
    // The same room (same seed) scaled: a 2.4-6 m box is 5-12 mm wide at 0.002.
    EXPECT_NEAR(huge / tiny, 1e4, 1e-6);
    EXPECT_LT(tiny, 0.02);
    EXPECT_GT(huge, 50.0);
}

TEST(StressRoom, OptionsOutOfRangeAreRefused) {
    auto refused = [](auto change) {
        StressRoomOptions o;
        change(o);
        EXPECT_THROW(makeStressRoom(o), std::invalid_argument);
    };
    refused([](StressRoomOptions& o) { o.scale = 0; });
    refused([](StressRoomOptions& o) { o.maxReflectance = 1; });
    refused([](StressRoomOptions& o) { o.grid = 0; });
    refused([](StressRoomOptions& o) { o.jitter = 0.002; });  // quads: no interior vertex
    refused([](StressRoomOptions& o) {
        o.triangles = true;
        o.grid = 3;
        o.jitter = stress::kMaxJitter;
    });
    refused([](StressRoomOptions& o) { o.floorBoxes = {3, 2}; });
}

// ---- the solver on stress rooms ----------------------------------------------------------

namespace {

struct Solved {
    SolverStats stats;
    std::vector<Rgb> B;  ///< every node's B
};

Solved solveRoom(const Scene& scene, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SolverOptions o;
    o.epsilon = 1e-3;
    o.maxRefineRounds = 8;  // the watchdog available today (no link budget yet)
    HierarchicalSolver solver(scene, o);
    solver.solve();
    Solved s{solver.stats(), {}};
    for (const Node& n : solver.hierarchy().nodes) s.B.push_back(n.B);
    return s;
}

/// Solves the room with 1 and 2 threads and checks what must hold in any room.
void checkSolve(const StressRoomOptions& o) {
    const StressRoom room = makeStressRoom(o);
    const Solved one = solveRoom(room.scene, 1);
    const Solved two = solveRoom(room.scene, 2);
    const SolverStats& st = one.stats;
    for (size_t i = 0; i < one.B.size(); ++i)
        ASSERT_TRUE(one.B[i].isFinite()) << "node " << i << " of " << one.B.size();
    // Energy: a closed room absorbs what its lamps emit, no more. The form factors of a
    // receiver point sum to at most 1 (exact contour integrals, visibility <= 1), and the
    // gather starts from zero, so a stopped iteration absorbs less, never more; 1 %
    // covers the approximations of cluster links (a cluster's form factor is estimated,
    // not integrated). A solver that creates energy exceeds it at once.
    for (int k = 0; k < 3; ++k) {
        ASSERT_GT(st.emittedPower[k], 0.0);
        EXPECT_LE(st.absorbedPower[k], 1.01 * st.emittedPower[k]) << "channel " << k;
    }
    // Thread count changes the schedule, never the result.
    ASSERT_EQ(one.B.size(), two.B.size());
    for (size_t i = 0; i < one.B.size(); ++i) ASSERT_EQ(one.B[i], two.B[i]) << "node " << i;
    EXPECT_EQ(st.links, two.stats.links);
}

StressRoomOptions solveCase(uint64_t seed, double scale, bool triangles, int grid, double jitter,
                            bool rotate) {
    StressRoomOptions o;
    o.seed = seed;
    o.scale = scale;
    o.triangles = triangles;
    o.grid = grid;
    o.jitter = jitter;
    o.rotate = rotate;
    return o;
}

}  // namespace

// Before the energy bound four of the five failed: seed 101 absorbed 4 % more than its
// lamps emit; seeds 102, 104 and 105 ran for more than two minutes (the 5 mm room reaching
// 5.6 GB).

TEST(StressRoomSolve, QuadsOneMetre) {
    checkSolve(solveCase(101, 1, false, 1, 0, false));
}
TEST(StressRoomSolve, TrianglesFiveMillimetreRoom) {
    checkSolve(solveCase(102, 0.002, true, 2, 0, false));
}
TEST(StressRoomSolve, JitteredTrianglesRotated) {
    checkSolve(solveCase(103, 1, true, 2, 0.002, true));
}
TEST(StressRoomSolve, QuadsHundredMetresRotated) {
    checkSolve(solveCase(104, 20, false, 1, 0, true));
}
TEST(StressRoomSolve, JitteredTrianglesHundredMetres) {
    checkSolve(solveCase(105, 20, true, 2, 0.002, false));
}

// Shaft tests turned off during a solve (SolverOptions::shaftPayoff) save their walks and
// change nothing: where a shaft is empty, every ray between the two ends passes as well,
// so the rays' verdict is the shaft's (VISIBLE, V = 1) and the refinement, the links and
// the solution are the same. A payoff of 1 turns them off once the solve has made
// kShaftSample tests, whatever they found; 0 never does.
TEST(StressRoomSolve, ShaftTestsTurnedOffChangeNoLinkAndNoRadiosity) {
    StressRoomOptions o = solveCase(106, 1, true, 2, 0.002, false);
    o.shelves = {2, 2};
    o.booksPerBoard = {10, 10};
    const StressRoom room = makeStressRoom(o);
    struct Run {
        std::vector<Rgb> B;
        size_t links = 0;
        uint64_t shaftTests = 0, rays = 0;
        bool saidOff = false;
    };
    const auto run = [&](double payoff) {
        SolverOptions so;
        so.shaftPayoff = payoff;
        Run r;
        so.progress = [&r](const std::string& m) {
            r.saidOff |= m.find("shaft tests off") != std::string::npos;
        };
        HierarchicalSolver solver(room.scene, so);
        solver.solve();
        for (const Node& n : solver.hierarchy().nodes) r.B.push_back(n.B);
        r.links = solver.links().size();
        r.shaftTests = solver.stats().shaftTests;
        r.rays = solver.stats().rays;
        return r;
    };
    const Run always = run(0), off = run(1);
    ASSERT_GE(always.shaftTests, HierarchicalSolver::kShaftSample) << "too few tests to decide";
    EXPECT_FALSE(always.saidOff);
    EXPECT_TRUE(off.saidOff);
    EXPECT_LT(off.shaftTests, always.shaftTests);  // the later batches tested none
    // Shafts after the stop were empty too, and their links cast rays: without them the
    // comparison below would hold trivially.
    EXPECT_GT(off.rays, always.rays);
    ASSERT_EQ(off.links, always.links);
    ASSERT_EQ(off.B.size(), always.B.size());
    for (size_t i = 0; i < off.B.size(); ++i) {
        ASSERT_EQ(off.B[i], always.B[i]) << "node " << i;
    }
}
