// Light reach (radiosity/light_reach.h): a lamp that lights the room reaches it; one below
// the floor (facing down into nothing, or up at the floor's back) or shut in a box does not.
#include "radiosity/light_reach.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "furnace.h"

namespace radiosity {
namespace {

/// A square face of side `side` centred on `c` in the plane z = c.z, facing up or down.
std::vector<Vec3> horizontalSquare(const Vec3& c, double side, bool up) {
    const double h = side / 2;
    std::vector<Vec3> v = {c + Vec3(-h, -h, 0), c + Vec3(-h, h, 0), c + Vec3(h, h, 0),
                           c + Vec3(h, -h, 0)};  // counter-clockwise seen from below
    if (up) std::reverse(v.begin(), v.end());
    return v;
}

/// A 4 x 3 x 2.5 m room (faces inward), a closed 0.5 m box on its floor (faces outward), and
/// lights added by addLight.
struct Room {
    Scene scene;

    Room() {
        scene.objects = {"room", "box", "lamps"};
        for (const auto& f : test::boxFacesInward(4, 3, 2.5))
            scene.polygons.push_back(makePolygon(f, 0, Rgb::gray(0.5)));
        for (auto f : test::boxFacesInward(0.5, 0.5, 0.5)) {
            std::reverse(f.begin(), f.end());  // outward
            for (Vec3& p : f) p += Vec3(2.5, 1, 0);
            scene.polygons.push_back(makePolygon(f, 1, Rgb::gray(0.5)));
        }
    }
    /// A light of one or more faces; returns its index.
    int addLight(const std::string& name, const std::vector<std::vector<Vec3>>& faces) {
        const int l = static_cast<int>(scene.lights.size());
        Light light{name, {}, Rgb::gray(10)};
        for (const auto& f : faces) {
            Polygon p = makePolygon(f, 2, Rgb{});
            p.light = l;
            light.polygons.push_back(static_cast<int>(scene.polygons.size()));
            scene.polygons.push_back(p);
        }
        scene.lights.push_back(light);
        return l;
    }
};

TEST(LightReach, ALampUnderTheCeilingReachesTheRoomAndMisplacedOnesDoNot) {
    Room room;
    const int ceiling =
        room.addLight("ceiling", {horizontalSquare(Vec3(1, 1.5, 2.45), 0.3, /*up=*/false)});
    const int belowDown =
        room.addLight("below, down", {horizontalSquare(Vec3(1, 1.5, -0.2), 0.3, false)});
    const int belowUp =
        room.addLight("below, up", {horizontalSquare(Vec3(1, 1.5, -0.2), 0.3, true)});
    const int inBox =
        room.addLight("in the box", {horizontalSquare(Vec3(2.75, 1.25, 0.2), 0.2, true)});
    const Visibility vis(room.scene);

    // A closed room: every ray from the lamp meets the front of a wall, the floor or the box.
    const LightReach lit = lightReach(room.scene, vis, ceiling);
    EXPECT_GE(lit.rays, 256);
    EXPECT_EQ(lit.hits, lit.rays);
    EXPECT_DOUBLE_EQ(lit.fraction, 1.0);
    // Below the floor facing down: nothing there. Facing up: the floor's back. In the box:
    // the backs of its faces. None of their light meets a surface's front.
    for (const int l : {belowDown, belowUp, inBox}) {
        const LightReach r = lightReach(room.scene, vis, l);
        EXPECT_GE(r.rays, 256) << room.scene.lights[static_cast<size_t>(l)].name;
        EXPECT_EQ(r.hits, 0) << room.scene.lights[static_cast<size_t>(l)].name;
        EXPECT_EQ(r.fraction, 0.0) << room.scene.lights[static_cast<size_t>(l)].name;
    }
}

TEST(LightReach, FacesCountByTheirArea) {
    // One light, two faces: 0.2 x 0.2 m under the ceiling facing the room, 0.4 x 0.4 m below
    // the floor facing its back. A quarter of its area, so of its emission, reaches the room.
    Room room;
    const int l = room.addLight("split", {horizontalSquare(Vec3(1, 1.5, 2.45), 0.2, false),
                                          horizontalSquare(Vec3(1, 1.5, -0.2), 0.4, true)});
    const Visibility vis(room.scene);
    const LightReach r = lightReach(room.scene, vis, l);
    EXPECT_NEAR(r.fraction, 0.2 * 0.2 / (0.2 * 0.2 + 0.4 * 0.4), 1e-12);
    EXPECT_EQ(r.hits * 2, r.rays);  // the same rays per face; all of the first one's hit
}

TEST(LightReach, ALightTheSceneLacksIsAnError) {
    Room room;
    const Visibility vis(room.scene);
    EXPECT_THROW(lightReach(room.scene, vis, 0), std::out_of_range);
    EXPECT_THROW(lightReach(room.scene, vis, -1), std::out_of_range);
}

}  // namespace
}  // namespace radiosity
