// Reflectance from a photo: recovering known reflectances from a synthetic photo.
#include <gtest/gtest.h>

#include "relight/item_buffer.h"
#include "relight/lighting_buffer.h"
#include "relight/reflectance.h"
#include "relight/scene_file.h"

using namespace relight;
using radiosity::Rgb;

TEST(Reflectance, RecoversKnownReflectancesFromASyntheticPhoto) {
    // The Cornell box with made-up reflectances, rendered by the engine itself (no noise),
    // is the photo; the estimate starts from grey 0.5 everywhere. The ceiling is lit only
    // by bounced light, where the undamped fixed point rho <- pi L / H(rho) never settles.
    SceneFile sf = loadScene(std::string(RELIGHT_DATA_DIR) + "/cornell");
    radiosity::Scene truthScene = sf.scene;
    for (size_t p = 0; p < truthScene.polygons.size(); ++p) {
        if (truthScene.polygons[p].light >= 0) continue;
        truthScene.polygons[p].rho =
            Rgb{0.30 + 0.05 * static_cast<double>(p % 9), 0.70 - 0.04 * static_cast<double>(p % 7),
                0.20 + 0.06 * static_cast<double>(p % 5)};
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
    int checked = 0;
    for (size_t p = 0; p < truthScene.polygons.size(); ++p) {
        const auto& truePoly = truthScene.polygons[p];
        if (truePoly.light >= 0) continue;
        const Rgb est = solver.scene().polygons[p].rho;
        // Only polygons the photo shows are estimated; the rest take the mean.
        bool seen = false;
        for (size_t i = 0; i < items.polygon.size() && !seen; ++i)
            seen = items.polygon[i] == static_cast<int>(p);
        if (!seen) continue;
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
}
