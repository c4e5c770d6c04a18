// Test fixture: the furnace, a closed box whose faces all emit and reflect.
#pragma once

#include <string>
#include <vector>

#include "radiosity/scene.h"

namespace radiosity::test {

/// A closed box [0,sx]x[0,sy]x[0,sz] with its six faces facing inwards
/// (counter-clockwise seen from inside).
inline std::vector<std::vector<Vec3>> boxFacesInward(double sx, double sy, double sz) {
    return {
        {{0, 0, 0}, {sx, 0, 0}, {sx, sy, 0}, {0, sy, 0}},      // floor, normal +z
        {{0, 0, sz}, {0, sy, sz}, {sx, sy, sz}, {sx, 0, sz}},  // ceiling, normal -z
        {{0, 0, 0}, {0, 0, sz}, {sx, 0, sz}, {sx, 0, 0}},      // y = 0, normal +y
        {{0, sy, 0}, {sx, sy, 0}, {sx, sy, sz}, {0, sy, sz}},  // y = sy, normal -y
        {{0, 0, 0}, {0, sy, 0}, {0, sy, sz}, {0, 0, sz}},      // x = 0, normal +x
        {{sx, 0, 0}, {sx, 0, sz}, {sx, sy, sz}, {sx, sy, 0}},  // x = sx, normal -x
    };
}

/// Furnace scene, a 1 x 1.3 x 0.8 m box: every face is a light of radiance L that also
/// reflects rho. In it B = pi L / (1 - rho) everywhere.
inline Scene furnace(double rho, double L) {
    Scene s;
    s.objects = {"box"};
    for (const auto& f : boxFacesInward(1.0, 1.3, 0.8)) {
        Polygon p = makePolygon(f, 0, Rgb::gray(rho));
        p.light = static_cast<int>(s.lights.size());
        s.lights.push_back({"face" + std::to_string(s.lights.size()),
                            {static_cast<int>(s.polygons.size())},
                            Rgb::gray(L)});
        s.polygons.push_back(p);
    }
    return s;
}

}  // namespace radiosity::test
