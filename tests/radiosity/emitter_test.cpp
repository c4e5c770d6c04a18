// The light model (radiosity/emitter.h): each type's direct irradiance against its closed
// form, shadows by Embree, and the edits.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radiosity/detail/form_factor.h"
#include "radiosity/emitter.h"
#include "radiosity/scene.h"
#include "radiosity/visibility.h"

using namespace radiosity;

namespace {

constexpr double kPi = std::numbers::pi;

/// A 4 m x 4 m floor (z = 0, up), optionally with a 2 m x 2 m roof at z = 1 over x, y in
/// [-1, 1] (facing down).
Scene floorScene(bool roof) {
    Scene s;
    s.objects = {"floor", "roof"};
    s.polygons.push_back(
        makePolygon({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0, Rgb::gray(0.5)));
    if (roof)
        s.polygons.push_back(
            makePolygon({{-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}}, 1, Rgb::gray(0.5)));
    return s;
}

Rgb at(const Emitter& e, const Visibility& vis, const Vec3& x, int rays = 64) {
    Rng rng(11);
    return e.irradiance(vis, {x, {0, 0, 1}, 0}, rays, rng);
}

/// A sky of constant radiance L: L(w) = c0 Y00 with Y00 = 1 / (2 sqrt(pi)).
Sh9Rgb constantSky(double L) {
    Sh9Rgb s;
    s.c[0] = Rgb::gray(L * 2 * std::sqrt(kPi));
    return s;
}

}  // namespace

TEST(Emitter, SunOnAFloorGivesItsIrradianceTimesSinElevation) {
    const Visibility vis(floorScene(false));
    for (double elevation : {90.0, 50.0, 20.0}) {
        const double t = elevation * kPi / 180;
        const Vec3 d{std::cos(t), 0.3 * std::cos(t), std::sin(t)};  // any azimuth
        const auto sun = makeSun("sun", d, 0.53, {4.5, 4.2, 3.7});
        const double sinEl = d.z / glm::length(d);
        const Rgb E = at(*sun, vis, {0.3, -0.2, 0});
        // Over a disc of half-angle a the mean cosine is cos(el) (1 - O(a^2)): 2e-5 for the
        // real sun, so 1e-4 relative holds.
        EXPECT_NEAR(E.r, 4.5 * sinEl, 1e-4 * 4.5) << elevation;
        EXPECT_NEAR(E.b, 3.7 * sinEl, 1e-4 * 3.7) << elevation;
        EXPECT_NEAR(sun->unoccludedIrradiance({{0, 0, 0}, {0, 0, 1}, 0}).g, 4.2 * sinEl, 1e-12);
    }
}

TEST(Emitter, SunUnderARoofIsShadowedAndItsPenumbraIsPartial) {
    const Visibility vis(floorScene(true));
    const auto sun = makeSun("sun", {0, 0, 1}, 10.0, Rgb::gray(2));
    EXPECT_EQ(at(*sun, vis, {0, 0, 0}).r, 0.0);            // under the roof's middle
    EXPECT_NEAR(at(*sun, vis, {1.8, 0, 0}).r, 2.0, 2e-2);  // well outside its shadow
    // On the shadow's edge (x = 1) half of the disc is hidden: E / 2 to within the
    // stratified estimate's error (256 directions, a straight edge across the disc: a few
    // per cent at most).
    EXPECT_NEAR(at(*sun, vis, {1, 0, 0}, 256).r, 1.0, 0.05);
}

TEST(Emitter, ConstantSkyOnAnOpenPlaneGivesPiL) {
    const Visibility vis(floorScene(false));
    const auto sky = makeEnvironment("sky", constantSky(0.7));
    // L constant and nothing in the way: every cosine-distributed ray returns L, so the
    // estimate pi mean(L) is exact to rounding.
    EXPECT_NEAR(at(*sky, vis, {0.5, 0.5, 0}).g, kPi * 0.7, 1e-12);
    EXPECT_NEAR(sky->unoccludedIrradiance({{0, 0, 0}, {0, 0, 1}, 0}).g, kPi * 0.7, 1e-12);
}

TEST(Emitter, SkyUnderARoofSeesOnlyWhatTheRoofLeaves) {
    const Visibility vis(floorScene(true));
    const auto sky = makeEnvironment("sky", constantSky(1.0));
    // Under the middle of a 2 x 2 roof 1 m up, the roof covers the form factor F of a
    // square seen from below its centre: E = pi L (1 - F), F exact by the contour integral.
    const Vec3 roof[4] = {{-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}};
    const double F = pointToPolygon({0, 0, 0}, {0, 0, 1}, roof, 4, {0, 0, -1});
    // 1024 stratified cosine directions: the share of the roof is found to within ~1 %.
    EXPECT_NEAR(at(*sky, vis, {0, 0, 0}, 1024).r, kPi * (1 - F), 0.01 * kPi);
}

TEST(Emitter, PointLampGivesIntensityCosOverDistanceSquared) {
    const Visibility vis(floorScene(false));
    const auto lamp = makePointLamp("P", {0.5, -0.3, 2.0}, {6, 5.2, 4});
    for (const Vec3 x : {Vec3{0, 0, 0}, Vec3{1.5, 1, 0}, Vec3{-1.9, -1.9, 0}}) {
        const Vec3 v = Vec3{0.5, -0.3, 2.0} - x;
        const double r2 = glm::dot(v, v), c = v.z / std::sqrt(r2);
        EXPECT_NEAR(at(*lamp, vis, x).r, 6 * c / r2, 1e-12);
        EXPECT_NEAR(at(*lamp, vis, x).b, 4 * c / r2, 1e-12);
    }
    const Visibility roofed(floorScene(true));
    EXPECT_EQ(at(*lamp, roofed, {0, 0, 0}).r, 0.0);  // the roof is in the way
    // Below the floor's plane the lamp is behind the receiver: no light.
    const auto under = makePointLamp("P", {0, 0, -1}, Rgb::gray(1));
    EXPECT_EQ(at(*under, vis, {0, 0, 0}).r, 0.0);
}

TEST(Emitter, QuadLampWithoutBlockersIsItsContourIntegral) {
    const Visibility vis(floorScene(false));
    // 1.5 m up: above the roof of floorScene(true).
    const std::vector<Vec3> face = {
        {-0.5, -0.5, 1.5}, {-0.5, 0.5, 1.5}, {0.5, 0.5, 1.5}, {0.5, -0.5, 1.5}};
    const auto lamp = makeQuadLamp("lamp", {face}, {}, Rgb::gray(3));
    const double F = pointToPolygon({0.2, 0.1, 0}, {0, 0, 1}, face.data(), 4, {0, 0, -1});
    EXPECT_NEAR(at(*lamp, vis, {0.2, 0.1, 0}).r, kPi * 3 * F, 1e-12);
    EXPECT_NEAR(lamp->power({}).r, kPi * 3 * 1.0, 1e-12);  // E A, E = pi L
    const Visibility roofed(floorScene(true));
    EXPECT_EQ(at(*lamp, roofed, {0, 0, 0}).r, 0.0);
}

TEST(Emitter, EditsApplyByTypeAndRefuseWhatATypeLacks) {
    auto sun = makeSun("sun", {0, 0, 1}, 0, Rgb::gray(2));
    EmitterEdit turn;
    turn.direction = Vec3{1, 0, 1};
    turn.scale = 0.5;
    sun->apply(turn);
    EXPECT_NEAR(sun->unoccludedIrradiance({{0, 0, 0}, {0, 0, 1}, -1}).r, 2 * 0.5 * std::sqrt(0.5),
                1e-12);
    EmitterEdit move;
    move.position = Vec3{0, 0, 1};
    EXPECT_THROW(sun->apply(move), std::invalid_argument);
    EmitterEdit off;
    off.scale = 0.0;
    sun->apply(off);
    EXPECT_FALSE(sun->on());

    auto lamp = makePointLamp("P", {0, 0, 1}, Rgb::gray(1));
    move.position = Vec3{0, 0, 2};
    lamp->apply(move);
    EXPECT_NEAR(lamp->unoccludedIrradiance({{0, 0, 0}, {0, 0, 1}, -1}).r, 0.25, 1e-12);
    EXPECT_THROW(lamp->apply(turn), std::invalid_argument);

    // The sky turned by 180 degrees about z: a sky brighter towards +x becomes brighter
    // towards -x (L11 is the x coefficient: its sign flips).
    Sh9Rgb s = constantSky(1);
    s.c[3] = Rgb::gray(0.3);
    auto sky = makeEnvironment("sky", s);
    EmitterEdit rot;
    rot.rotate = EmitterEdit::Rotation{{0, 0, 1}, 180};
    sky->apply(rot);
    const Rgb east = sky->unoccludedIrradiance({{0, 0, 0}, {1, 0, 0}, -1});
    const Rgb west = sky->unoccludedIrradiance({{0, 0, 0}, {-1, 0, 0}, -1});
    EXPECT_NEAR(west.r - east.r, 2 * (2 * kPi / 3) * 0.3 * std::sqrt(3 / (4 * kPi)), 1e-9);
    EXPECT_THROW(sky->apply(move), std::invalid_argument);
    EmitterEdit negative;
    negative.scale = -1.0;
    EXPECT_THROW(lamp->apply(negative), std::invalid_argument);
}
