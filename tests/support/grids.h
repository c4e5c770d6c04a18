// A surface cut into an n x n grid of triangle pairs that share their corners, as a
// reconstruction's mesh cuts one: `at(i, j)` (0 <= i, j <= n) gives the grid's corners.
#pragma once

#include "radiosity/scene.h"

namespace radiosity::test {

template <class At>
void addTriangleGrid(Scene& s, int n, At&& at, int object, const Rgb& rho) {
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            s.polygons.push_back(
                makePolygon({at(i, j), at(i + 1, j), at(i + 1, j + 1)}, object, rho));
            s.polygons.push_back(
                makePolygon({at(i, j), at(i + 1, j + 1), at(i, j + 1)}, object, rho));
        }
}

}  // namespace radiosity::test
