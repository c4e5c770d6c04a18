// Reflectance from a photo: recovering known reflectances from a synthetic photo, per
// polygon and per leaf element.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>

#include "relight/io/scene_file.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/reflectance.h"
#include "relight/relighting.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;
using radiosity::Rgb;

TEST(Reflectance, RecoversKnownReflectancesFromASyntheticPhoto) {
    // The Cornell box with made-up reflectances, one per object (an object is one
    // material), rendered by the engine itself (no noise), is the photo; the estimate starts
    // from grey 0.5 everywhere. The ceiling is lit only by bounced light, where the undamped
    // fixed point rho <- pi L / H(rho) never settles.
    SceneFile sf = loadScene(RELIGHT_DATA_DIR "/cornell");
    radiosity::Scene truthScene = sf.scene;
    for (auto& poly : truthScene.polygons) {
        if (poly.light >= 0) continue;
        const auto o = static_cast<double>(poly.object);
        poly.rho = Rgb{0.30 + 0.05 * std::fmod(o, 9.0), 0.70 - 0.04 * std::fmod(o, 7.0),
                       0.20 + 0.06 * std::fmod(o, 5.0)};
    }
    radiosity::SolverOptions o;
    o.epsilon = 1e-4;
    radiosity::HierarchicalSolver truthSolver(truthScene, o);
    truthSolver.solve();
    const ItemBuffer items =
        castItemBuffer(sf.camera, truthSolver.scene(), truthSolver.visibility(), 4);
    LightingBuffer truthLighting = computeLightingBuffer(items, truthSolver);
    updateIndirect(truthLighting, truthSolver);
    const Image photo = renderRadiosity(items, truthLighting, truthSolver.scene());

    radiosity::Scene start = sf.scene;
    for (auto& poly : start.polygons)
        if (poly.light < 0) poly.rho = Rgb::gray(0.5);
    radiosity::HierarchicalSolver solver(start, o);
    solver.solve();
    const LightingBuffer lighting = computeLightingBuffer(items, solver);
    const ReflectanceReport rep = estimatePolygonReflectance(solver, sf, items, lighting, photo);
    EXPECT_GE(rep.polygonsSeen, 10);
    EXPECT_LT(rep.lastChange, 1e-3) << "did not converge in " << rep.rounds << " rounds";
    int checked = 0, hidden = 0;
    for (size_t p = 0; p < truthScene.polygons.size(); ++p) {
        const auto& truePoly = truthScene.polygons[p];
        if (truePoly.light >= 0) continue;
        const Rgb est = solver.scene().polygons[p].rho;
        // Polygons the photo shows are estimated; the blocks' hidden faces (their backs and
        // the tall block's top) take the mean of their own object's seen faces, which is
        // their object's reflectance here.
        bool seen = false;
        for (size_t i = 0; i < items.polygon.size() && !seen; ++i)
            seen = items.polygon[i] == static_cast<int>(p);
        if (!seen) ++hidden;
        for (int c = 0; c < 3; ++c) {
            // 5 % relative (measured: 0.3 % median, 3.5 % at worst). The two solutions'
            // subdivisions differ (refinement follows the reflectances it saw on the way),
            // so their indirect light differs by the hierarchical solution's own error at
            // epsilon 1e-4, most on faces lit mainly by bounced light; the iteration's
            // stopping tolerance (1e-3) and the sampled indirect mean add less.
            EXPECT_NEAR(est[c] / truePoly.rho[c], 1.0, 0.05) << "polygon " << p << " channel " << c;
        }
        ++checked;
    }
    EXPECT_GE(checked, 10);
    EXPECT_GE(hidden, 3);
}

TEST(Reflectance, EachLeafTakesTheReflectanceOfItsOwnTexture) {
    // A two-tone floor: the room's photo with every floor pixel on the side x < x_mid of the
    // floor at half its value, as if half the floor were painted darker. One reflectance
    // per polygon cannot show this; per leaf (Loscos et al. 2000, §4.2: the reflectance is
    // set up per element after refinement) the leaves wholly on the dark side get half
    // the reflectance of those wholly on the other side. Tolerance 0.05 on the ratio of
    // the two sides' mean reflectance: rho = pi c / H uses H interpolated between a leaf's
    // corners, and H itself changes a little (the dark half reflects less light onto the
    // rest), but both sides see the same lamps, so these errors largely cancel in the ratio.
    const std::filesystem::path room = RELIGHT_DATA_DIR "/room";
    test::TempDir dir;
    for (const char* f : {"scene.json", "room.obj", "photo.mask.png"})
        std::filesystem::copy_file(room / f, dir.path() / f);
    SceneFile sf = loadScene(room);
    const radiosity::Scene& scene = sf.scene;
    int floorObject = -1;
    for (size_t i = 0; i < scene.objects.size(); ++i)
        if (scene.objects[i] == "floor") floorObject = static_cast<int>(i);
    ASSERT_GE(floorObject, 0);
    double xmin = 1e30, xmax = -1e30;
    for (const auto& poly : scene.polygons)
        if (poly.object == floorObject)
            for (int i = 0; i < poly.vertexCount; ++i) {
                xmin = std::min(xmin, poly.v[i].x);
                xmax = std::max(xmax, poly.v[i].x);
            }
    const double xmid = 0.5 * (xmin + xmax);
    auto onFloor = [&](int p) { return p >= 0 && scene.polygons[p].object == floorObject; };

    Image photo = loadFirstPhoto(sf);
    {
        radiosity::HierarchicalSolver s(scene, {});
        const ItemBuffer items = castItemBuffer(sf.camera, s.scene(), s.visibility(), 4);
        for (int y = 0; y < items.height; ++y)
            for (int x = 0; x < items.width; ++x) {
                bool dark = true;
                for (int k = 0; k < items.spp && dark; ++k) {
                    const int idx = items.sampleIndex(x, y, k);
                    dark = onFloor(items.polygon[idx]) && items.point[idx].x < xmid;
                }
                if (dark)
                    for (int c = 0; c < 3; ++c) photo.at(x, y)[c] *= 0.5f;
            }
    }
    writeImage(dir.path() / "photo.exr", photo);

    RelightOptions o = test::coarseOptions();
    o.shadowRemoval = false;  // removal changes the reflectance in shadows: not the subject
    const auto r = prepareRelighting(loadScene(dir.path()), o);
    const auto& h = r->solver->hierarchy();
    Rgb sum[2];
    int count[2] = {0, 0};
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        const auto& node = h.nodes[n];
        if (node.isCluster() || !node.isLeaf() || !onFloor(node.polygon)) continue;
        if (r->texture->samples(n) < o.leafReflectanceSamples) continue;
        bool left = true, right = true;
        for (int i = 0; i < node.vertexCount; ++i) {
            const double x = r->mesh->vertices()[r->mesh->corners(n)[i]].position.x;
            left = left && x < xmid;
            right = right && x > xmid;
        }
        if (!left && !right) continue;
        sum[left ? 0 : 1] += node.rho;
        ++count[left ? 0 : 1];
    }
    ASSERT_GE(count[0], 10);
    ASSERT_GE(count[1], 10);
    for (int c = 0; c < 3; ++c) {
        const double ratio = (sum[0][c] / count[0]) / (sum[1][c] / count[1]);
        EXPECT_NEAR(ratio, 0.5, 0.05) << "channel " << c;
    }
}

TEST(Reflectance, ASetUpThatCannotEndInTimeIsGivenUpAndChangesNothing) {
    // The set-up (the photo's sums, the gather points' final gathers) is given up at
    // ReflectanceOptions::until: with a deadline already past, nothing is estimated,
    // every polygon keeps the scene's reflectance and the solver its radiosities, exactly
    // (nothing ran), and the report says so. A deadline far off changes nothing either way:
    // the estimate is the one without a deadline, exactly (the same arithmetic).
    SceneFile sf = loadScene(RELIGHT_DATA_DIR "/cornell");
    radiosity::SolverOptions o;
    radiosity::HierarchicalSolver solver(sf.scene, o);
    solver.solve();
    const ItemBuffer items = castItemBuffer(sf.camera, solver.scene(), solver.visibility(), 4);
    const LightingBuffer lighting = computeLightingBuffer(items, solver);
    const Image photo = loadFirstPhoto(sf);
    std::vector<Rgb> B0;
    for (const auto& n : solver.hierarchy().nodes) B0.push_back(n.B);
    ReflectanceOptions late;
    late.until = radiosity::Clock::now() - std::chrono::milliseconds(1);
    const ReflectanceReport rep =
        estimatePolygonReflectance(solver, sf, items, lighting, photo, late);
    EXPECT_TRUE(rep.skipped);
    EXPECT_EQ(rep.rounds, 0);
    for (size_t p = 0; p < sf.scene.polygons.size(); ++p)
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(solver.scene().polygons[p].rho[c], sf.scene.polygons[p].rho[c]) << p;
    for (size_t n = 0; n < B0.size(); ++n)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(solver.hierarchy().nodes[n].B[c], B0[n][c]) << n;

    auto rhoAfter = [&](const ReflectanceOptions& ro) {
        radiosity::HierarchicalSolver s(sf.scene, o);
        s.solve();
        const ReflectanceReport r = estimatePolygonReflectance(s, sf, items, lighting, photo, ro);
        EXPECT_FALSE(r.skipped);
        std::vector<Rgb> rho;
        for (const auto& poly : s.scene().polygons) rho.push_back(poly.rho);
        return rho;
    };
    ReflectanceOptions inTime;
    inTime.until = radiosity::Clock::now() + std::chrono::hours(1);
    const std::vector<Rgb> a = rhoAfter(inTime), b = rhoAfter({});
    ASSERT_EQ(a.size(), b.size());
    for (size_t p = 0; p < a.size(); ++p)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(a[p][c], b[p][c]) << p;
}

namespace {

/// The Cornell box with a photo 40 % darker than its reflectances say, which the estimate
/// does not match in one round; estimate() runs estimatePolygonReflectance from a fresh
/// solve with the given options and returns the report and every polygon's reflectance.
struct DarkCornell {
    SceneFile sf = loadScene(RELIGHT_DATA_DIR "/cornell");
    radiosity::SolverOptions o;
    ItemBuffer items;
    Image photo;

    DarkCornell() {
        o.epsilon = 1e-4;
        radiosity::HierarchicalSolver truthSolver(sf.scene, o);
        truthSolver.solve();
        items = castItemBuffer(sf.camera, truthSolver.scene(), truthSolver.visibility(), 4);
        LightingBuffer truthLighting = computeLightingBuffer(items, truthSolver);
        updateIndirect(truthLighting, truthSolver);
        photo = renderRadiosity(items, truthLighting, truthSolver.scene());
        for (float& v : photo.rgb) v *= 0.6f;  // darker than the scene's reflectances say
    }

    /// `within`: ReflectanceOptions::until that long after the solve, when the estimate
    /// begins; `took`: how long the estimate took.
    ReflectanceReport estimate(ReflectanceOptions ro, std::vector<Rgb>* rho,
                               std::optional<radiosity::Clock::duration> within = {},
                               radiosity::Clock::duration* took = nullptr) const {
        radiosity::HierarchicalSolver solver(sf.scene, o);
        solver.solve();
        const LightingBuffer lighting = computeLightingBuffer(items, solver);
        const auto t0 = radiosity::Clock::now();
        if (within) ro.until = t0 + *within;
        const ReflectanceReport rep =
            estimatePolygonReflectance(solver, sf, items, lighting, photo, ro);
        if (took) *took = radiosity::Clock::now() - t0;
        for (const auto& poly : solver.scene().polygons) rho->push_back(poly.rho);
        return rep;
    }
};

void expectSameReflectances(const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t p = 0; p < a.size(); ++p)
        for (int c = 0; c < 3; ++c)
            // The same arithmetic on the same inputs; 1e-9 allows for the order of parallel
            // sums, far below the change one round makes (the photo is 40 % darker).
            EXPECT_NEAR(a[p][c], b[p][c], 1e-9) << "polygon " << p << " channel " << c;
}

}  // namespace

TEST(Reflectance, ATimeBudgetStopsAfterACompleteRound) {
    // The rounds' time budget (estimatePolygonReflectance's `seconds`, a share of
    // --time-budget) is checked between rounds only: a budget spent at once leaves the
    // solution of exactly one complete round (every polygon's reflectance set, then solved),
    // the same as asking for one round, and the report says the budget cut in; without a
    // budget the same photo takes more rounds.
    const DarkCornell scene;
    auto estimate = [&](int rounds, double seconds, std::vector<Rgb>* rho) {
        ReflectanceOptions ro;
        ro.rounds = rounds;
        ro.seconds = seconds;
        return scene.estimate(ro, rho);
    };
    std::vector<Rgb> cut, one, full;
    const ReflectanceReport repCut = estimate(12, 1e-9, &cut);
    const ReflectanceReport repOne = estimate(1, 0, &one);
    const ReflectanceReport repFull = estimate(12, 0, &full);
    EXPECT_TRUE(repCut.budgetReached);
    EXPECT_EQ(repCut.rounds, 1);
    EXPECT_FALSE(repOne.budgetReached);  // one round asked, one done: no cut
    EXPECT_FALSE(repFull.budgetReached);
    EXPECT_GT(repFull.rounds, 1) << "the photo must need more than one round for this test";
    expectSameReflectances(cut, one);
}

TEST(Reflectance, ADeadlineLeavesWholeRoundsOnly) {
    // ReflectanceOptions::until owes no round: wherever it falls, the solution is that of
    // the complete rounds done (the same as asking for that many rounds without it), and
    // the report says when it cut in. Deadlines at fractions of the time the whole estimate
    // takes fall in the set-up, in a round's sums or between rounds, whichever the
    // machine's speed makes it; the property holds at each. A deadline already past
    // estimates nothing.
    const DarkCornell scene;
    std::vector<Rgb> full;
    radiosity::Clock::duration whole{};
    const ReflectanceReport repFull = scene.estimate({}, &full, {}, &whole);
    ASSERT_GT(repFull.rounds, 2) << "the photo must need several rounds for this test";
    for (double fraction : {0.0, 0.7, 0.8, 0.9, 0.95}) {
        SCOPED_TRACE(fraction);
        const auto within =
            std::chrono::duration_cast<radiosity::Clock::duration>(whole * fraction);
        std::vector<Rgb> cut, same;
        const ReflectanceReport rep = scene.estimate({}, &cut, within);
        if (fraction == 0.0) {
            EXPECT_TRUE(rep.skipped);
        }
        EXPECT_TRUE(rep.skipped || rep.rounds == repFull.rounds || rep.budgetReached);
        ReflectanceOptions asMany;
        asMany.rounds = rep.rounds;
        if (rep.rounds == 0) {
            for (const auto& poly : scene.sf.scene.polygons) same.push_back(poly.rho);
        } else {
            scene.estimate(asMany, &same);
        }
        expectSameReflectances(cut, same);
    }
}

TEST(Reflectance, ADeadlinePassedBetweenRoundsBeginsNoOther) {
    // The check between rounds, made deterministic: the deadline is far (three times the
    // whole estimate) but the progress report of round 2 waits until it has passed, so
    // that no round fits after it. The solution is exactly that of two rounds.
    const DarkCornell scene;
    std::vector<Rgb> full, two, cut;
    radiosity::Clock::duration whole{};
    ASSERT_GT(scene.estimate({}, &full, {}, &whole).rounds, 2);
    ReflectanceOptions ro;
    int reports = 0;
    ro.progress = [&](const std::string&) {
        if (++reports == 2) std::this_thread::sleep_for(3 * whole + std::chrono::milliseconds(50));
    };
    const ReflectanceReport rep = scene.estimate(ro, &cut, 3 * whole);
    EXPECT_EQ(rep.rounds, 2);
    EXPECT_TRUE(rep.budgetReached);
    ReflectanceOptions asTwo;
    asTwo.rounds = 2;
    scene.estimate(asTwo, &two);
    expectSameReflectances(cut, two);
}
