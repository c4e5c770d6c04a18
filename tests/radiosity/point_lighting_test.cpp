// Per-point lighting: DirectLight (per-point direct light) and the final gather.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "furnace.h"
#include "radiosity/detail/form_factor.h"
#include "radiosity/direct_light.h"
#include "radiosity/final_gather.h"
#include "radiosity/solver.h"

using namespace radiosity;
using radiosity::test::furnace;

namespace {

/// A 4 m x 4 m floor (z = 0, facing up) under a 1 m x 1 m light at z = 1 facing down,
/// centred over the origin; optionally a plate at z = 0.5 over x in [-2, 0], facing down
/// (it reflects floor light back: the floor's indirect light).
Scene lampOverFloor(bool plate) {
    Scene s;
    s.objects = {"floor", "plate", "lamp"};
    s.polygons.push_back(
        makePolygon({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0, Rgb::gray(0.5)));
    if (plate)
        s.polygons.push_back(makePolygon({{-2, -2, 0.5}, {-2, 2, 0.5}, {0, 2, 0.5}, {0, -2, 0.5}},
                                         1, Rgb::gray(0.5)));
    Polygon lamp =
        makePolygon({{-0.5, -0.5, 1}, {-0.5, 0.5, 1}, {0.5, 0.5, 1}, {0.5, -0.5, 1}}, 2, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(3.0)});
    s.polygons.push_back(lamp);
    return s;
}

}  // namespace

TEST(DirectLight, UnoccludedEqualsTheContourIntegralWithoutRays) {
    HierarchicalSolver solver(lampOverFloor(false), {});
    solver.solve();
    const DirectLight direct(solver);
    const Polygon& lamp = solver.scene().polygons[1];
    for (const Vec3 x : {Vec3{0, 0, 0}, Vec3{1.3, -0.7, 0}, Vec3{-1.9, 1.9, 0}}) {
        double G = -1;
        direct.geometry(0, x, 7, &G);
        const double F = pointToPolygon(x, {0, 0, 1}, lamp.v.data(), 4, lamp.normal);
        // Same function, same arguments: equal to rounding.
        EXPECT_NEAR(G, F, 1e-12) << x.x << " " << x.y;
    }
    // Nothing stands between floor and lamp: every shaft is empty, no ray is needed.
    EXPECT_EQ(direct.raysCast(), 0u);
}

TEST(DirectLight, HalfHiddenLampGivesHalfItsFormFactor) {
    // From the origin, the plate over x < 0 at half height hides exactly the half x < 0 of
    // the lamp, so V = 1/2 and G = F / 2. The estimate is a fraction of stratified rays:
    // averaged over 64 seeds it must be within 0.05 of 1/2 (the spread of one estimate is
    // at most 0.14 when the first 4 rays agree, so 0.05 is more than 3 standard errors).
    HierarchicalSolver solver(lampOverFloor(true), {});
    solver.solve();
    const DirectLight direct(solver);
    const Polygon& lamp = solver.scene().polygons[2];
    const Vec3 x{0, 0, 0};
    const double F = pointToPolygon(x, {0, 0, 1}, lamp.v.data(), 4, lamp.normal);
    double sum = 0;
    for (uint64_t seed = 0; seed < 64; ++seed) {
        double G = -1;
        direct.geometry(0, x, seed, &G);
        ASSERT_GE(G, 0.0);
        ASSERT_LE(G, F + 1e-12);
        sum += G / F;
    }
    EXPECT_NEAR(sum / 64, 0.5, 0.05);
    // A point far under the plate sees none of the lamp.
    double G = -1;
    direct.geometry(0, Vec3{-1.5, 0, 0}, 1, &G);
    EXPECT_EQ(G, 0.0);
}

TEST(DirectLight, IsGeometryOnly) {
    // G does not depend on the light's radiance, and a light that is off still has it:
    // switching it on needs no new rays.
    Scene on = lampOverFloor(true), off = lampOverFloor(true);
    off.lights[0].radiance = Rgb{};
    HierarchicalSolver a(on, {}), b(off, {});
    a.solve();
    b.solve();
    const DirectLight da(a), db(b);
    for (const Vec3 x : {Vec3{0.7, 0.2, 0}, Vec3{1.5, -1, 0}}) {
        double Ga = -1, Gb = -1;
        da.geometry(0, x, 3, &Ga);
        db.geometry(0, x, 3, &Gb);
        EXPECT_GT(Ga, 0.0);
        EXPECT_NEAR(Ga, Gb, 1e-12);
    }
}

TEST(FinalGather, FurnaceGivesEOverOneMinusRhoAtEveryPoint) {
    // In the closed furnace box B = E / (1 - rho) everywhere. Per point, the direct form
    // factors to the other five faces sum to 1 (contour integrals), and the links of the
    // element chain cover every source once, so the gathered B must match within 2e-3:
    // the solver's own 1e-3 plus the point form factors of element links summing to 1
    // only up to the quadrature of clipped contours near edges.
    for (double rho : {0.3, 0.8}) {
        SolverOptions o;
        o.epsilon = 1e-3;
        o.tolerance = 1e-5;
        HierarchicalSolver solver(furnace(rho, 1.0), o);
        solver.solve();
        const DirectLight direct(solver);
        const double expected = std::numbers::pi / (1.0 - rho);
        // Centre, near an edge and near a corner of the floor (polygon 0).
        for (const Vec3 x : {Vec3{0.5, 0.65, 0}, Vec3{0.01, 0.65, 0}, Vec3{0.99, 1.29, 0}}) {
            const Rgb B = gatheredRadiosity(solver, direct, 0, x, 11);
            EXPECT_NEAR(B.r / expected, 1.0, 2e-3) << "rho " << rho << " at " << x.x << "," << x.y;
            // The gather by rays: every ray, whatever it hits, brings the reflected part
            // B - E = rho B, the same everywhere: exact but for the solver's tolerance.
            uint64_t rays = 0;
            const Rgb H = rayGatherIndirect(solver, 0, x, 8, 3, &rays);
            EXPECT_NEAR(H.r / (rho * expected), 1.0, 2e-3) << "ray gather, rho " << rho;
            EXPECT_EQ(rays, 64u);
        }
    }
}

TEST(FinalGather, SmoothAcrossElementBoundaries) {
    // The element grid must not show. Across the boundary between two floor leaves, the
    // gathered indirect light 1 mm either side must differ by less than a quarter of its
    // difference between the two leaves' centres (piecewise-constant B would jump by all
    // of it). Only boundaries where the centres differ by more than 2 % are judged.
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver solver(lampOverFloor(true), o);
    solver.solve();
    const Hierarchy& h = solver.hierarchy();
    auto H = [&](const Vec3& x) { return finalGatherIndirect(solver, 0, x, 16).r; };
    int tested = 0;
    for (const Node& n : h.nodes) {
        if (n.isCluster() || !n.isLeaf() || n.polygon != 0) continue;
        const double xb = n.bounds.hi.x;  // the leaf's +x edge
        if (xb >= 1.99) continue;
        const double y = n.centre.y;
        const Vec3 a{xb - 1e-3, y, 0}, b{xb + 1e-3, y, 0};
        const int other = h.locateLeaf(0, b);
        if (other == h.locateLeaf(0, a)) continue;
        const double ca = H(Vec3{n.centre.x, y, 0}), cb = H(Vec3{h.nodes[other].centre.x, y, 0});
        ASSERT_GT(ca, 0.0);
        if (std::abs(cb - ca) < 0.02 * ca) continue;
        EXPECT_LT(std::abs(H(b) - H(a)), 0.25 * std::abs(cb - ca)) << "boundary x = " << xb;
        ++tested;
    }
    EXPECT_GT(tested, 3);
}

TEST(RayGather, APartlyHiddenWallLightsAPointWithThePartItSees) {
    // A 4 m wall lit by a lamp near its top is bright above and dim below; a 1 m screen in
    // front of it hides its lower part from the floor behind the screen. The ray gather
    // reads the leaves' radiosity where each ray lands, so its mean over points agrees with
    // a reference summed leaf by leaf: B times the point's form factor to the leaf (contour
    // integral) times its visibility from 256 points weighed by the kernel. The wall's lit
    // band is 20 times brighter than the rest and a small target: one point's gather by 256
    // rays varies by 5-10 %; 21 points x 1024 rays bring the mean's noise to about 1 %, and
    // 3 % allows for the reference's own sampling.
    Scene s;
    s.objects = {"floor", "wall", "screen", "lamp"};
    s.polygons.push_back(
        makePolygon({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(
        makePolygon({{-2, 2, 0}, {2, 2, 0}, {2, 2, 4}, {-2, 2, 4}}, 1, Rgb::gray(0.8)));
    s.polygons.push_back(
        makePolygon({{-2, 1, 0}, {-2, 1, 1}, {2, 1, 1}, {2, 1, 0}}, 2, Rgb::gray(0.1)));
    Polygon lamp = makePolygon(
        {{-0.5, 1.2, 3.9}, {-0.5, 1.8, 3.9}, {0.5, 1.8, 3.9}, {0.5, 1.2, 3.9}}, 3, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(10.0)});
    s.polygons.push_back(lamp);
    SolverOptions o;
    o.epsilon = 1e-3;
    HierarchicalSolver solver(s, o);
    solver.solve();
    const Hierarchy& h = solver.hierarchy();
    const Vec3 up{0, 0, 1};
    double gathered = 0, reference = 0;
    for (double x = -1.5; x <= 1.5; x += 0.5)
        for (double y : {-1.5, -1.0, -0.5}) {
            const Vec3 p{x, y, 0};
            gathered += rayGatherIndirect(solver, 0, p, 32, static_cast<uint64_t>(100 * x + y)).r;
            for (size_t n = 0; n < h.nodes.size(); ++n) {
                const Node& e = h.nodes[n];
                if (e.isCluster() || !e.isLeaf() || e.polygon == 0 || e.emitting) continue;
                const double F = pointToPolygon(p, up, e.v.data(), e.vertexCount, e.normal);
                if (!(F > 0)) continue;
                // The leaf's visible share, each of its 16 x 16 points weighed by the form
                // factor's kernel cos cos / d^2 there (a leaf half hidden near the screen's
                // edge sends more through its nearer half).
                double seen = 0, all = 0;
                for (int i = 0; i < 16; ++i)
                    for (int j = 0; j < 16; ++j) {
                        const Vec3 q =
                            h.samplePoint(static_cast<int>(n), (i + 0.5) / 16, (j + 0.5) / 16, 0.5);
                        const Vec3 d = q - p;
                        const double d2 = glm::dot(d, d);
                        const double w = std::max(0.0, glm::dot(d, up)) *
                                         std::max(0.0, -glm::dot(d, e.normal)) / (d2 * d2);
                        all += w;
                        if (solver.visibility().visible(p, q, 0, e.polygon)) seen += w;
                    }
                if (all > 0) reference += e.B.r * F * seen / all;
            }
        }
    ASSERT_GT(reference, 0);
    EXPECT_NEAR(gathered / reference, 1.0, 0.03);
    // The links' final gather, for the record (what the ray gather replaces at the display's
    // vertices): it brings the wall's mean radiosity through its coarse links.
    double links = 0;
    for (double x = -1.5; x <= 1.5; x += 0.5)
        for (double y : {-1.5, -1.0, -0.5})
            links += finalGatherIndirect(solver, 0, {x, y, 0}, 4, 7).r;
    std::printf("ray gather / reference %.4f, links' final gather / reference %.4f\n",
                gathered / reference, links / reference);
}

TEST(RayGather, PerLightResponsesAddUpToTheGather) {
    // rayGatherResponses is the same rays per unit radiance of each light: weighted by the
    // lights' radiances (those of the solution) they give rayGatherIndirect's value.
    HierarchicalSolver solver(lampOverFloor(true), SolverOptions{});
    solver.solve();
    const LightResponses responses(solver);
    const Vec3 x{-1.0, 0.3, 0};
    Rgb H[1];
    rayGatherResponses(solver, responses, 0, x, H, 8, 5);
    const Rgb direct = rayGatherIndirect(solver, 0, x, 8, 5);
    EXPECT_NEAR((H[0] * 3.0).r, direct.r, 1e-3 * direct.r);  // the lamp's radiance is 3
}
