// Test scene shared by the energy-bound test and bench/leak_l_room: an L-shaped
// enclosure lit in one arm only.
#pragma once

#include <string>
#include <vector>

#include "radiosity/scene.h"

namespace radiosity::test {

/// An L-shaped enclosure, 1 m high: arm A along x ([0,4] x [0,1]), arm B along y
/// ([0,1] x [1,4]); closed, all faces inward, rho 0.6, one lamp under the ceiling at the
/// far end of arm A.
inline Scene lRoom() {
    Scene s;
    s.objects = {"L", "lamp"};
    const Rgb rho = Rgb::gray(0.6);
    auto quad = [&](std::vector<Vec3> q) { s.polygons.push_back(makePolygon(q, 0, rho)); };
    const double H = 1.0;
    // Floor (+z) and ceiling (-z) of both arms.
    quad({{0, 0, 0}, {4, 0, 0}, {4, 1, 0}, {0, 1, 0}});
    quad({{0, 1, 0}, {1, 1, 0}, {1, 4, 0}, {0, 4, 0}});
    quad({{0, 0, H}, {0, 1, H}, {4, 1, H}, {4, 0, H}});
    quad({{0, 1, H}, {0, 4, H}, {1, 4, H}, {1, 1, H}});
    // Walls along the outline (0,0) (4,0) (4,1) (1,1) (1,4) (0,4), each facing inward.
    const std::vector<Vec3> outline{{0, 0, 0}, {4, 0, 0}, {4, 1, 0},
                                    {1, 1, 0}, {1, 4, 0}, {0, 4, 0}};
    for (size_t i = 0; i < outline.size(); ++i) {
        const Vec3 a = outline[i], b = outline[(i + 1) % outline.size()];
        quad({a, a + Vec3{0, 0, H}, b + Vec3{0, 0, H}, b});
    }
    const double z = H - 0.01;
    Polygon lamp =
        makePolygon({{3.4, 0.3, z}, {3.4, 0.7, z}, {3.8, 0.7, z}, {3.8, 0.3, z}}, 1, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(10.0)});
    s.polygons.push_back(lamp);
    return s;
}

}  // namespace radiosity::test
