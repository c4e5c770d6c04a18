// Test scene shared by the per-light oracle's test and bench/shaded_lamp: the cut room
// (cut_room.h, its ceiling lamp the strong light) with a weak lamp in a closed shade of thin
// sheets, as the stair hall's table lamp (issue 30): none of the weak lamp's light may leave
// the shade. Objects: 3 the shade's outward faces, 4 its inward faces, 5 the lamp.
#pragma once

#include <algorithm>

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

}  // namespace radiosity::test
