// Test scene shared by the per-light oracle's and the narrowed sources' tests and
// bench/shaded_lamp: the cut room
// (cut_room.h, its ceiling lamp the strong light) with a weak lamp in a closed shade of thin
// sheets, as the stair hall's table lamp (issue 30): none of the weak lamp's light may leave
// the shade. Objects: 3 the shade's outward faces, 4 its inward faces, 5 the lamp.
#pragma once

#include <algorithm>

#include "radiosity/light_response.h"
#include "radiosity/solver.h"
#include "tests/support/cut_room.h"

namespace radiosity::test {

/// The cut room with a second lamp, a 10 cm quad facing down, inside a closed 40 x 40 x
/// 30 cm shade standing 0.8 m above the floor; each face of the shade cut 2 x 2, as a
/// sheet: a face outward (object "shade_out") and its twin inward ("shade_in").
inline Scene shadedLampRoom(int cut) {
    Scene s = test::cutRoom(cut, 0.5, /*box=*/false);
    s.objects.push_back("shade_out");   // 3
    s.objects.push_back("shade_in");    // 4
    s.objects.push_back("table_lamp");  // 5
    const Vec3 o{1.8, 1.3, 0.8};
    for (auto f : test::boxFacesInward(0.4, 0.4, 0.3)) {
        for (Vec3& p : f) p += o;
        test::addCutQuad(s, f, 2, 4, Rgb::gray(0.5));  // inward: the lamp's side
        std::reverse(f.begin(), f.end());
        test::addCutQuad(s, f, 2, 3, Rgb::gray(0.5));  // outward: the room's side
    }
    Polygon lamp = makePolygon({{o.x + 0.15, o.y + 0.15, o.z + 0.25},
                                {o.x + 0.15, o.y + 0.25, o.z + 0.25},
                                {o.x + 0.25, o.y + 0.25, o.z + 0.25},
                                {o.x + 0.25, o.y + 0.15, o.z + 0.25}},
                               5, Rgb{});
    lamp.light = 1;
    s.lights.push_back({"table_lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(100.0)});
    s.polygons.push_back(lamp);
    return s;
}

/// The shaded (weak) lamp's light that the surfaces outside its shade reflect, all bounces,
/// over what the lamp emits: 0 in truth (the shade is closed). `links` gets the solution's.
inline double shadedLampLeak(const SolverOptions& o, int* links) {
    const Scene scene = shadedLampRoom(8);
    HierarchicalSolver solver(scene, o);
    solver.solve();
    *links = solver.stats().links;
    const LightResponses R(solver);
    const auto& nodes = solver.hierarchy().nodes;
    double outside = 0;
    for (size_t n = 0; n < nodes.size(); ++n) {
        const Node& e = nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        const int obj = scene.polygons[static_cast<size_t>(e.polygon)].object;
        if (obj == 4 || obj == 5) continue;  // the shade's inside, the lamp
        outside += R.reflected(static_cast<int>(n))[1].maxComponent() * e.area;
    }
    // The lamp's 10 cm quad at unit radiance emits pi L A; the outside's rho is 0.5.
    return outside / 0.5 / (3.141592653589793 * 0.01);
}

}  // namespace radiosity::test
