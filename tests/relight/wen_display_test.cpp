// Wen, Liu & Huang 2003's display (DisplayMode::wen, relight/display/wen_display.h): the
// sky's part of each pixel's light is the unoccluded irradiance E(n) of its 9 coefficients
// at the pixel's normal, where the default per-pixel display uses the occluded transfer
// (radiosity/sky_transfer.h) and its bounces. Two scenes lit by a sky alone, a grey photo,
// the camera looking straight down: a floor alone, where both displays must agree to the
// transfer's ray noise, and the same floor against a wall, where the sky turned behind the
// wall darkens the floor at its foot in the default display and not in Wen's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "radiosity/sh9.h"
#include "relight/display/wen_display.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "temp_dir.h"
#include "tests/support/skies.h"

namespace relight {
namespace {

using nlohmann::json;
using radiosity::Rgb;
using radiosity::Sh9Rgb;
using radiosity::Vec3;

/// A floor (x from x0 to 6 m, y from -4 to 4 m, facing up) and, with `wall`, a wall 3 m
/// high along x = 0 facing +x.
std::string geometry(bool wall) {
    std::ostringstream o;
    const double x0 = wall ? 0.0 : -2.0;
    o << "o floor\nv " << x0 << " -4 0\nv 6 -4 0\nv 6 4 0\nv " << x0 << " 4 0\nf 1 2 3 4\n";
    if (wall) o << "o wall\nv 0 -4 0\nv 0 4 0\nv 0 4 3\nv 0 -4 3\nf 5 6 7 8\n";
    return o.str();
}

/// The camera 5 m above (2.5, 0, 0) looking down (OpenCV: x right, y down, z forward):
/// world x to the right, world -y down the image.
json sceneJson() {
    json sky = json::array();
    for (const Rgb& c : radiosity::test::clearSky().c) sky.push_back({c.r, c.g, c.b});
    return {{"format", "relight-scene/1"},
            {"geometry", {"scene.obj"}},
            {"camera",
             {{"width", 80},
              {"height", 60},
              {"K", {{60.0, 0.0, 39.5}, {0.0, 60.0, 29.5}, {0.0, 0.0, 1.0}}},
              {"world_to_camera", {{1, 0, 0, -2.5}, {0, -1, 0, 0}, {0, 0, -1, 5}}}}},
            {"photos", {{{"file", "photo.exr"}, {"lights_on", {"sky"}}}}},
            {"average_reflectance", 0.5},
            {"lights", {{{"name", "sky"}, {"type", "environment"}, {"sh9", sky}}}}};
}

struct Prepared {
    test::TempDir dir{"wen_display"};
    std::unique_ptr<Relighting> r;
};

/// The scene prepared with per-pixel light (relight render's settings: 16 samples per
/// pixel) from a grey photo: the displays' ratios are then the light's alone.
std::unique_ptr<Prepared> prepare(bool wall) {
    auto p = std::make_unique<Prepared>();
    p->dir.write("scene.obj", geometry(wall));
    Image photo(80, 60);
    for (float& v : photo.rgb) v = 0.3f;
    writeImage(p->dir.path() / "photo.exr", photo);
    std::istringstream in(sceneJson().dump());
    RelightOptions o;
    o.pixelLight = true;
    p->r = prepareRelighting(parseScene(in, p->dir.path()), o);
    return p;
}

/// The radiance of every light (the sky's 9 coefficients) for `sky`.
std::vector<Rgb> skyRadiance(const Sh9Rgb& sky) {
    return {sky.c.begin(), sky.c.end()};
}

}  // namespace

TEST(WenDisplay, KeepsEachPixelsNormalAndTheSkysCoefficients) {
    const auto s = prepare(false);
    const PreparedImage& p = s->r->prepared;
    ASSERT_EQ(p.skyCoefficient.size(), 9u);
    for (int k = 0; k < 9; ++k) EXPECT_EQ(p.skyCoefficient[static_cast<size_t>(k)], k);
    int drawn = 0;
    for (size_t px = 0; px < p.photo.rgb.size() / 3; ++px) {
        if (!shownPerPixel(p.display, px)) continue;
        ++drawn;
        EXPECT_EQ(p.pixelNormal[3 * px + 2], 1.0f) << px;  // the floor's normal, +z
    }
    EXPECT_EQ(drawn, 80 * 60);  // the floor fills the view
}

TEST(WenDisplay, OnAFloorAloneItIsTheDefaultDisplayToTheTransfersRayNoise) {
    const auto s = prepare(false);
    const PreparedImage& p = s->r->prepared;
    // The sky tilted by 60 degrees about x: E(+z) changes (L10 and L20 mix with the others).
    const auto L =
        skyRadiance(radiosity::sh9RotateAboutAxis(radiosity::test::clearSky(), Vec3{1, 0, 0}, 60));
    Image wen, pixel;
    renderEdit(p, L, wen, DisplayMode::wen);
    renderEdit(p, L, pixel, DisplayMode::pixel);
    // Nothing occludes the floor and nothing reflects light onto it, so the default
    // display's sky light differs from E(n) by the transfer's estimate alone: 16 stratified
    // cosine rays per sample (kDefaultMaxRays), whose per-coefficient rms error is about
    // 0.1 (sky_transfer_test.cpp measured 6.2e-3 at 256 rays, falling as 1 / N on an
    // unoccluded plane), averaged over the pixel's 16 samples: 0.025 per coefficient, about
    // 1.1 % of E = 1.45 for this sky's coefficients, in the photo's light and the edit's
    // alike. Bounds: 5 % for any pixel (4.5 sigma of the ratio of the two), 1 % for the
    // mean of the absolute difference. A wrong A_l or basis is off by 10 % or more.
    double sum = 0, worst = 0;
    int n = 0;
    for (size_t px = 0; px < p.photo.rgb.size() / 3; ++px) {
        if (!shownPerPixel(p.display, px)) continue;
        for (size_t c = 0; c < 3; ++c) {
            const double a = wen.rgb[3 * px + c], b = pixel.rgb[3 * px + c];
            const double rel = std::abs(a - b) / b;
            sum += rel;
            worst = std::max(worst, rel);
            ++n;
        }
    }
    ASSERT_GT(n, 0);
    std::printf("floor alone: wen against pixel, mean %.4f, largest %.4f\n", sum / n, worst);
    EXPECT_LT(sum / n, 0.01);
    EXPECT_LT(worst, 0.05);
    // The edit changes the light by more than that: the test would see a display that
    // ignored it.
    double changed = 0;
    for (size_t i = 0; i < wen.rgb.size(); ++i)
        changed += std::abs(static_cast<double>(wen.rgb[i]) / 0.3 - 1);
    EXPECT_GT(changed / static_cast<double>(wen.rgb.size()), 0.1);
}

TEST(WenDisplay, AtAWallsFootTheSkyTurnedBehindItDarkensOnlyTheOccludedDisplay) {
    const auto s = prepare(true);
    const PreparedImage& p = s->r->prepared;
    // The clear sky is brighter towards +x, the side the floor sees; turned by 180 degrees
    // about z its bright side is -x, behind the wall.
    const Sh9Rgb sky = radiosity::test::clearSky();
    const auto L = skyRadiance(radiosity::sh9RotateAboutAxis(sky, Vec3{0, 0, 1}, 180));
    Image wen, pixel;
    renderEdit(p, L, wen, DisplayMode::wen);
    renderEdit(p, L, pixel, DisplayMode::pixel);
    // E(+z) does not change under a turn about z (Y_k(+z) is 0 for every k with an x or y),
    // so Wen's display keeps the photo on the floor (float rounding: 1e-5).
    // At the wall's foot the floor sees the +x half of the sky alone, so the occluded
    // display scales it by E_-x / E_+x, the half-skies' cosine-weighted irradiances (plus
    // the wall's bounced light, which darkens too: the wall faces +x).
    auto half = [&](double sign) {
        return radiosity::sh9ProjectRgb(
                   [&](const Vec3& w) {
                       return w.z > 0 && sign * w.x > 0 ? radiosity::sh9Eval(sky, w) * w.z : Rgb{};
                   },
                   64)
                   .c[0] *
               (2 * std::sqrt(std::numbers::pi));  // integral = L00 coefficient / Y00
    };
    const Rgb ePlus = half(1), eMinus = half(-1);
    const double expected = eMinus.g / ePlus.g;
    ASSERT_LT(expected, 0.9);  // the test means something only if the halves differ
    const Camera& cam = s->r->scene.camera;
    double sumNear = 0, sumFar = 0;
    int near = 0, far = 0;
    for (double y = -1.5; y <= 1.5; y += 0.25)
        for (const double x : {0.08, 4.5}) {
            double u = 0, v = 0, depth = 0;
            ASSERT_TRUE(cam.project(Vec3{x, y, 0}, u, v, depth));
            const size_t px =
                static_cast<size_t>(std::floor(v)) * 80 + static_cast<size_t>(std::floor(u));
            ASSERT_TRUE(shownPerPixel(p.display, px));
            EXPECT_NEAR(wen.rgb[3 * px + 1], 0.3, 3e-6) << "x " << x << " y " << y;
            const double ratio = pixel.rgb[3 * px + 1] / wen.rgb[3 * px + 1];
            (x < 1 ? sumNear : sumFar) += ratio;
            ++(x < 1 ? near : far);
        }
    const double meanNear = sumNear / near, meanFar = sumFar / far;
    std::printf("wall's foot: occluded / unoccluded %.3f (half skies %.3f), 4.5 m out %.3f\n",
                meanNear, expected, meanFar);
    // 8 cm from a 3 m wall the floor sees 97 % of the -x half's elevation blocked: the
    // ratio is at most half-way from 1 to the half skies' ratio, and darker than far out.
    EXPECT_LT(meanNear, 1 - 0.5 * (1 - expected));
    EXPECT_LT(meanNear, meanFar);
}

}  // namespace relight
