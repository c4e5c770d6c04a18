// Solver tests: analytic answers (furnace), conservation, determinism.
#include "radiosity/solver.h"
#include "furnace.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

using namespace radiosity;

using radiosity::test::boxFacesInward;
using radiosity::test::furnace;

TEST(Furnace, FixtureFacesPointInwards) {
    for (const auto& f : boxFacesInward(1.0, 1.3, 0.8)) {
        const Vec3 n = glm::cross(f[1] - f[0], f[2] - f[0]);
        const Vec3 c = (f[0] + f[1] + f[2] + f[3]) * 0.25;
        EXPECT_GT(glm::dot(n, Vec3{0.5, 0.65, 0.4} - c), 0.0);
    }
}

TEST(Furnace, ClosedBoxGivesEOverOneMinusRho) {
    // In a closed box with uniform emittance E and reflectance rho, B = E / (1 - rho)
    // everywhere. Tolerance 1e-3 relative, as required: the form factors of one receiver
    // sum to 1 exactly (contour integrals), so what is left is the stopping error of the
    // sweeps (tolerance 1e-5 on its geometric estimate) and rounding.
    for (double rho : {0.0, 0.5, 0.8, 0.95}) {
        SolverOptions o;
        o.epsilon = 1e-3;
        o.tolerance = 1e-5;
        HierarchicalSolver solver(furnace(rho, 1.0), o);
        solver.solve();
        const double expected = std::numbers::pi / (1.0 - rho);
        const Hierarchy& h = solver.hierarchy();
        int leaves = 0;
        for (const Node& n : h.nodes) {
            if (n.isCluster() || !n.isLeaf()) continue;
            ++leaves;
            ASSERT_NEAR(n.B.r / expected, 1.0, 1e-3)
                << "rho " << rho << " leaf at level " << n.level;
        }
        if (rho > 0) {
            EXPECT_GT(leaves, 6) << "refinement must have subdivided the faces";
        }
        // Conservation: in a closed box all emitted power is absorbed (within 1e-3). For
        // rho = 0 the solver skips every link (nothing is reflected, so nothing needs
        // gathering) and the absorbed power is not measured.
        if (rho == 0) continue;
        const SolverStats st = solver.stats();
        EXPECT_NEAR(st.absorbedPower.r / st.emittedPower.r, 1.0, 1e-3) << "rho " << rho;
    }
}

TEST(Solver, DeterministicWhateverTheThreadCount) {
    // Same input, 1 thread and 2 threads: bit-identical radiosity and the same links.
    auto run = [](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        Scene s = furnace(0.6, 2.0);
        // Emit from one face only so the solution is not uniform.
        for (size_t i = 1; i < s.lights.size(); ++i) s.lights[i].radiance = Rgb{};
        HierarchicalSolver solver(s, {});
        solver.solve();
        std::vector<double> B;
        for (const Node& n : solver.hierarchy().nodes) B.push_back(n.B.r + 3 * n.B.g);
        return std::make_pair(B, solver.links().size());
    };
    const auto a = run(1), b = run(2);
    ASSERT_EQ(a.second, b.second);
    ASSERT_EQ(a.first.size(), b.first.size());
    for (size_t i = 0; i < a.first.size(); ++i) ASSERT_EQ(a.first[i], b.first[i]) << i;
}

TEST(Solver, DarkReceiversAreRefinedFinerDownToTheFloor) {
    // SolverOptions::darkFloor: a receiver darker than the mean radiosity has its BF
    // threshold lowered in proportion, down to darkFloor times epsilon. In a furnace lit by
    // one face, the faces far from it are darker than the mean: the solve refines more than
    // the plain criterion (darkFloor 1), and less than the plain criterion at epsilon times
    // the floor, which refines every receiver that finely.
    const auto run = [](double epsilon, double darkFloor) {
        Scene s = furnace(0.6, 2.0);
        for (size_t i = 1; i < s.lights.size(); ++i) s.lights[i].radiance = Rgb{};
        SolverOptions o;
        o.epsilon = epsilon;
        o.darkFloor = darkFloor;
        HierarchicalSolver solver(s, o);
        solver.solve();
        return std::make_pair(solver.links().size(), solver.stats());
    };
    const auto plain = run(1e-3, 1.0), dark = run(1e-3, 0.1), fine = run(1e-4, 1.0);
    EXPECT_GT(dark.first, plain.first);
    EXPECT_LT(dark.first, fine.first);
    EXPECT_GT(dark.second.leaves, plain.second.leaves);
}
