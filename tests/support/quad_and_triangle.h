// A two-polygon scene shared by the tests of the element hierarchy's geometry (header only).
#pragma once

#include "radiosity/scene.h"

namespace radiosity::test {

/// A skewed convex quad (not a parallelogram: its bilinear map is not affine, and its cut
/// lines are not parallel to its edges) and a tilted triangle, on two objects.
inline Scene quadAndTriangle() {
    Scene s;
    s.objects = {"quad", "tri"};
    s.polygons.push_back(
        makePolygon({{0, 0, 0}, {2, 0.2, 0}, {1.7, 1.5, 0}, {0.1, 1.1, 0}}, 0, Rgb::gray(0.5)));
    s.polygons.push_back(makePolygon({{0, 0, 1}, {1, 0, 1.5}, {0, 1, 1}}, 1, Rgb::gray(0.5)));
    return s;
}

}  // namespace radiosity::test
