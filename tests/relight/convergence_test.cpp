// Hierarchical radiosity against the full-matrix reference on the bundled Cornell box.
#include <gtest/gtest.h>

#include "radiosity/reference_solver.h"
#include "radiosity/solver.h"
#include "relight/io/scene_file.h"

using namespace radiosity;

TEST(Convergence, CornellErrorDecreasesWithEpsilon) {
    const relight::SceneFile sf = relight::loadScene(std::string(RELIGHT_DATA_DIR) + "/cornell");
    ReferenceOptions ro;
    ro.maxArea = 0.004;  // ~1000 elements: 1 M pairs, about a second on one core
    ReferenceSolver ref(sf.scene, ro);
    ref.solve();
    std::vector<double> errors;
    for (double eps : {1e-3, 1e-4, 1e-5}) {
        SolverOptions o;
        o.epsilon = eps;
        HierarchicalSolver hr(sf.scene, o);
        hr.solve();
        errors.push_back(
            relativeRmsError(ref, [&](int p, const Vec3& x) { return hr.radiosityAt(p, x); }));
    }
    // Each tenfold decrease of epsilon must cut the error by at least 15 %: measured cuts
    // are 40-50 % per decade; 15 % leaves room for the reference's own discretisation
    // error, which bounds how small the difference can get.
    EXPECT_LT(errors[1], 0.85 * errors[0]) << errors[0] << " -> " << errors[1];
    EXPECT_LT(errors[2], 0.85 * errors[1]) << errors[1] << " -> " << errors[2];
    // And the finest setting is within 10 % of the reference (measured 0.05).
    EXPECT_LT(errors[2], 0.10);
}
