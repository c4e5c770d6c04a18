// An axis-aligned box's six faces for tests: counter-clockwise seen from outside (fronts
// outward), in the order -z, +z, -y, +y, +x, -x.
#pragma once

#include <vector>

#include "radiosity/scene.h"

namespace radiosity::test {

inline std::vector<Polygon> box(const Vec3& lo, const Vec3& hi, int object, const Rgb& rho) {
    const Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                       {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                       {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
    const int f[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                         {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    std::vector<Polygon> out;
    for (const auto& q : f)
        out.push_back(makePolygon({c[q[0]], c[q[1]], c[q[2]], c[q[3]]}, object, rho));
    return out;
}

}  // namespace radiosity::test
