// Hierarchical radiosity against the full-matrix reference on the bundled Cornell box.
#include <gtest/gtest.h>

#include "radiosity/reference_solver.h"
#include "radiosity/solver.h"
#include "relight/io/scene_file.h"

using namespace radiosity;

TEST(Convergence, CornellErrorDecreasesWithEpsilon) {
    const relight::SceneFile sf = relight::loadScene(RELIGHT_DATA_DIR "/cornell");
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

TEST(Convergence, CornellSurfacesHoldTheReferencesLightAtTheDefaultEpsilon) {
    // Each large surface's mean radiosity (floor, ceiling, walls) against the full-matrix
    // reference at relight's epsilon. The ceiling is lit by indirect light only, through
    // coarse links that every leaf of it gathers a few per cent short, each within the 2-3 %
    // error of its own `seen` measurement: the row bound moved none of them, and the
    // ceiling was 4.5 % dark (0.955). Moved as a group, by their area mean's far smaller
    // error (HierarchicalSolver::groupRowScales), it is 0.978 (bench/surface_levels). 3 %:
    // above the reference's own discretisation (the ceiling's ratio moves by at most 0.23 %
    // between 0.004, 0.002 and 0.001 m^2 elements: bench/RESULTS.md), below the shortfall.
    const relight::SceneFile sf = relight::loadScene(RELIGHT_DATA_DIR "/cornell");
    ReferenceOptions ro;
    ro.maxArea = 0.004;
    ReferenceSolver ref(sf.scene, ro);
    ref.solve();
    SolverOptions o;
    o.epsilon = 1e-4;
    HierarchicalSolver hr(sf.scene, o);
    hr.solve();
    const size_t P = sf.scene.polygons.size();
    std::vector<double> mean(P, 0.0), meanRef(P, 0.0);
    const Hierarchy& h = ref.hierarchy();
    for (int id : ref.leaves()) {
        const Node& e = h.nodes[id];
        if (e.rho.maxComponent() <= 0) continue;
        const Rgb b = elementMean(e, [&](int p, const Vec3& x) { return hr.radiosityAt(p, x); });
        mean[static_cast<size_t>(e.polygon)] += e.area * (b.r + b.g + b.b);
        meanRef[static_cast<size_t>(e.polygon)] += e.area * (e.B.r + e.B.g + e.B.b);
    }
    int large = 0;
    for (size_t p = 0; p < P; ++p) {
        if (sf.scene.polygons[p].area < 0.1 || !(meanRef[p] > 0)) continue;
        ++large;
        EXPECT_NEAR(mean[p] / meanRef[p], 1.0, 0.03) << "polygon " << p;
    }
    EXPECT_EQ(large, 6);  // floor, ceiling, back wall, left wall, the right wall in two parts
}
