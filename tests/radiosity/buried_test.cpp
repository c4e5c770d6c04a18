// findBuriedPolygons / removeBuriedPolygons (radiosity/buried.h): the faces inside closed
// solids, which no light reaches and no eye sees, found and taken out; every face that can
// see out kept.
#include "radiosity/buried.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "radiosity/contact_split.h"
#include "tests/support/boxes.h"

using namespace radiosity;

namespace {

std::vector<Polygon> box(Vec3 lo, Vec3 hi, int object) {
    return radiosity::test::box(lo, hi, object, Rgb::gray(0.5));  // tests/support/boxes.h
}

/// A 4 x 4 m slab 0.2 m thick (object 0), its top at z = 0, and a 0.2 m thick wall box
/// (object 1) standing on it across its whole width at x in [2, 2.2], 2 m high: the slab's
/// top is cut along the wall's feet (contact_split.h), and the piece under the wall, with
/// the wall's foot, lies inside solid matter.
Scene slabAndWall() {
    Scene s;
    s.objects = {"slab", "wall"};
    s.polygons = box({0, 0, -0.2}, {4, 4, 0}, 0);
    const std::vector<Polygon> wall = box({2, 0, 0}, {2.2, 4, 2}, 1);
    s.polygons.insert(s.polygons.end(), wall.begin(), wall.end());
    splitAtContacts(s.polygons, s.polygons.size());
    return s;
}

bool near(const Vec3& a, const Vec3& b) {
    return glm::length(a - b) < 1e-9;
}

/// Indices of the faces of s whose centroid is `c` and normal `n`.
std::vector<int> facesAt(const Scene& s, const Vec3& c, const Vec3& n) {
    std::vector<int> out;
    for (size_t i = 0; i < s.polygons.size(); ++i)
        if (near(s.polygons[i].centroid(), c) && near(s.polygons[i].normal, n))
            out.push_back(static_cast<int>(i));
    return out;
}

std::vector<int> buried(const Scene& s, const BuriedContext& context = {}) {
    const Visibility vis(s);
    return findBuriedPolygons(s, s.polygons.size(), vis, context);
}

}  // namespace

TEST(Buried, TheSlabUnderAWallAndTheWallsFootAreFoundAndNothingElse) {
    const Scene s = slabAndWall();
    const std::vector<int> under = facesAt(s, {2.1, 2, 0}, {0, 0, 1});  // the slab's piece
    const std::vector<int> foot = facesAt(s, {2.1, 2, 0}, {0, 0, -1});  // the wall's bottom
    ASSERT_EQ(under.size(), 1u);
    ASSERT_EQ(foot.size(), 1u);
    std::vector<int> expected{under[0], foot[0]};
    std::sort(expected.begin(), expected.end());
    // The two open pieces of the slab's top, its sides and bottom, the wall's sides and top
    // all see out: nothing but the two faces in the contact is buried.
    EXPECT_EQ(buried(s), expected);
}

TEST(Buried, AFaceOfAnObjectAnEditMayRemoveIsNotSolidMatter) {
    // With the wall removable, the slab's piece under it would come to light: it is kept.
    // The wall's own foot still lies on solid slab: it is buried (it leaves with the wall).
    const Scene s = slabAndWall();
    BuriedContext context;
    context.mayVanish = {false, true};
    const std::vector<int> foot = facesAt(s, {2.1, 2, 0}, {0, 0, -1});
    EXPECT_EQ(buried(s, context), foot);
}

TEST(Buried, AFaceTheCameraSeesIsKept) {
    // A camera standing inside the wall box (a model's wall a little off the real one) looks
    // down onto the slab's piece under it through the wall's back faces: that piece is kept.
    const Scene s = slabAndWall();
    BuriedContext context;
    context.eye = Vec3{2.1, 1.5, 1.6};
    const std::vector<int> foot = facesAt(s, {2.1, 2, 0}, {0, 0, -1});
    EXPECT_EQ(buried(s, context), foot);
}

TEST(Buried, ARoomOfSheetWallsAndAnOpenBoxKeepEveryFace) {
    // Walls modelled as two faces back to back (a sheet): a ray meets a back face and a front
    // face at one distance, passes through the pair and escapes. A box without its lid: its
    // inside faces see the sky. Neither is solid matter around a face.
    Scene s;
    s.objects = {"room"};
    std::vector<Polygon> walls = box({0, 0, 0}, {4, 4, 3}, 0);  // fronts outward
    for (const Polygon& p : std::vector<Polygon>(walls)) {
        std::vector<Vec3> reversed(p.v.rbegin(), p.v.rend());
        walls.push_back(makePolygon(reversed, 0, p.rho));  // fronts inward
    }
    s.polygons = walls;
    std::vector<Polygon> open = box({1, 1, 0.5}, {2, 2, 1}, 0);
    open.erase(open.begin() + 1);  // no lid
    for (Polygon& p : open) {      // the inside faces
        std::vector<Vec3> reversed(p.v.rbegin(), p.v.rend());
        s.polygons.push_back(makePolygon(reversed, 0, p.rho));
    }
    EXPECT_TRUE(buried(s).empty());
}

TEST(Buried, RemovingThemRenumbersTheLightsFacesAndReturnsTheirArea) {
    Scene s = slabAndWall();
    const size_t geometry = s.polygons.size();
    s.lights.push_back({"lamp", {static_cast<int>(geometry)}, Rgb::gray(1)});
    Polygon lamp =
        makePolygon({{1, 1, 1.9}, {1, 1.5, 1.9}, {1.5, 1.5, 1.9}, {1.5, 1, 1.9}}, 0, Rgb{});
    lamp.light = 0;
    s.polygons.push_back(lamp);
    const Visibility vis(s);
    const std::vector<int> b = findBuriedPolygons(s, geometry, vis, {});
    ASSERT_EQ(b.size(), 2u);
    const double area = removeBuriedPolygons(s, b);
    EXPECT_NEAR(area, 2 * 0.2 * 4, 1e-12);  // the slab's piece and the wall's foot
    ASSERT_EQ(s.polygons.size(), geometry - 1);
    EXPECT_EQ(s.lights[0].polygons, std::vector<int>{static_cast<int>(geometry - 2)});
    EXPECT_EQ(s.polygons.back().light, 0);
}
