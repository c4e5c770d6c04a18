// Test scene shared by the energy-bound test and bench/closed_room: a closed room cut into
// triangles, as a reconstruction gives it, lit by one lamp in the ceiling.
#pragma once

#include <algorithm>
#include <vector>

#include "radiosity/scene.h"
#include "tests/radiosity/furnace.h"

namespace radiosity::test {

/// Cuts quad q (4 corners, counter-clockwise) into an n x n grid of triangle pairs, as a
/// reconstructed mesh comes; appends them to the scene as object `object`.
inline void addCutQuad(Scene& s, const std::vector<Vec3>& q, int n, int object, const Rgb& rho) {
    auto at = [&](double u, double v) {
        return (1 - u) * (1 - v) * q[0] + u * (1 - v) * q[1] + u * v * q[2] + (1 - u) * v * q[3];
    };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double u0 = double(i) / n, u1 = double(i + 1) / n;
            const double v0 = double(j) / n, v1 = double(j + 1) / n;
            s.polygons.push_back(makePolygon({at(u0, v0), at(u1, v0), at(u1, v1)}, object, rho));
            s.polygons.push_back(makePolygon({at(u0, v0), at(u1, v1), at(u0, v1)}, object, rho));
        }
}

/// A 4 x 3 x 2.5 m closed room, each face cut into `cut` x `cut` triangle pairs, with a
/// 1.2 x 0.8 x 0.7 m box standing on the floor (faces outward, bottom in contact with the
/// floor; left out without `box`). The lamp is the middle cell of the ceiling cut 3 x 3,
/// facing down: no surface shows its back to the room, so that what the room does not
/// absorb is an error.
inline Scene cutRoom(int cut, double rho, bool box = true) {
    Scene s;
    s.objects = {"room", "box", "lamp"};
    const auto faces = boxFacesInward(4, 3, 2.5);
    for (size_t f = 0; f < faces.size(); ++f) {
        if (f != 1) {
            addCutQuad(s, faces[f], cut, 0, Rgb::gray(rho));
            continue;
        }
        const auto& q = faces[f];  // the ceiling, cut 3 x 3
        auto at = [&](double u, double v) {
            return (1 - u) * (1 - v) * q[0] + u * (1 - v) * q[1] + u * v * q[2] +
                   (1 - u) * v * q[3];
        };
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                const std::vector<Vec3> cell{at(i / 3.0, j / 3.0), at((i + 1) / 3.0, j / 3.0),
                                             at((i + 1) / 3.0, (j + 1) / 3.0),
                                             at(i / 3.0, (j + 1) / 3.0)};
                if (i != 1 || j != 1) {
                    addCutQuad(s, cell, std::max(1, cut / 3), 0, Rgb::gray(rho));
                    continue;
                }
                Polygon lamp = makePolygon(cell, 2, Rgb{});
                lamp.light = 0;
                s.lights.push_back(
                    {"lamp", {static_cast<int>(s.polygons.size())}, Rgb::gray(10.0)});
                s.polygons.push_back(lamp);
            }
    }
    if (!box) return s;
    const Vec3 o{1.0, 1.0, 0.0};
    for (auto f : boxFacesInward(1.2, 0.8, 0.7)) {
        std::reverse(f.begin(), f.end());  // inward faces reversed face outward
        for (Vec3& p : f) p += o;
        addCutQuad(s, f, std::max(1, cut / 2), 1, Rgb::gray(rho));
    }
    return s;
}

}  // namespace radiosity::test
