// The per-pixel display (relight/pipeline/pixel_light.h): the photo given back exactly for
// its own lighting, a light edit nearer the path-traced truth than the vertex ratio
// display, and the prepared state's cache keeping what it needs.
#include "relight/pipeline/pixel_light.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <utility>
#include <vector>

#include "relight/display/debug_views.h"
#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/io/prepared_cache.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;
using radiosity::Rgb;

namespace {

const std::string kRoom = RELIGHT_DATA_DIR "/room";

/// The room prepared with per-pixel light, shared by the test files (room_fixture.h).
const Relighting& pixelRoom() {
    return test::coarsePixelRoom();
}

}  // namespace

TEST(PixelLight, ThePhotosOwnLightingGivesThePhotoBack) {
    // Same radiances in numerator and denominator: the ratio is exactly 1 at every surface
    // pixel, so the display is T there, bit for bit; emitting faces show their radiance.
    const PreparedImage& p = pixelRoom().prepared;
    ASSERT_EQ(p.pixelDirect.size(), static_cast<size_t>(p.photo.width) *
                                        static_cast<size_t>(p.photo.height) *
                                        p.photoRadiance.size());
    const Image out = renderEdit(p, p.photoRadiance, DisplayMode::pixel);
    int surface = 0;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            const size_t px =
                static_cast<size_t>(y) * static_cast<size_t>(out.width) + static_cast<size_t>(x);
            if (p.display.emitterStart[px] != p.display.emitterStart[px + 1] ||
                p.display.unshaded[px] > 0)
                continue;
            ++surface;
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(out.at(x, y)[c], std::max(p.photo.at(x, y)[c], 0.0f)) << x << "," << y;
        }
    EXPECT_GT(surface, out.width * out.height / 2);
}

TEST(PixelLight, ALightEditIsNearerTheTruthThanTheVertexRatio) {
    // back_off: the two back lamps off. The photo's shadows (table, cabinet) divide out at
    // each pixel rather than between leaf vertices. Measured at the default settings: 0.0126
    // against 0.0174 for the ratio display (bench/RESULTS.md); at the tests' coarse ones
    // here the per-pixel display must stay within 0.02 and below the ratio display.
    const Relighting& r = pixelRoom();
    const EditFile e = loadEdit(kRoom + "/edits/back_off.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    int w = r.prepared.photo.width, h = r.prepared.photo.height;
    const Image truth = readImage(kRoom + "/truth/back_off.exr");
    const auto maskT = readMask(kRoom + "/truth/back_off.mask.png", w, h);
    const auto maskP = readMask(kRoom + "/photo.mask.png", w, h);
    const Score pixel = scoreImage(renderEdit(r.prepared, radiance, DisplayMode::pixel), truth,
                                   r.prepared.photo, maskT, maskP);
    const Score ratio = scoreImage(renderEdit(r.prepared, radiance, DisplayMode::ratio), truth,
                                   r.prepared.photo, maskT, maskP);
    std::printf("back_off: pixel %.4f, ratio %.4f\n", pixel.relRmse, ratio.relRmse);
    EXPECT_LT(pixel.relRmse, ratio.relRmse);
    EXPECT_LE(pixel.relRmse, 0.02);
}

TEST(PixelLight, TheCacheKeepsItAndAPreparationWithoutItRefusesTheMode) {
    const Relighting& r = pixelRoom();
    const test::TempDir dir("relight_pixel_light_test");
    const auto file = dir.path() / "prepared.bin";
    writePreparedCache(file, r.prepared, 42);
    std::string why;
    const auto back = readPreparedCache(file, 42, &why);
    ASSERT_TRUE(back) << why;
    const EditFile e = loadEdit(kRoom + "/edits/colours.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    const Image a = renderEdit(*back, radiance, DisplayMode::pixel);
    const Image b = renderEdit(r.prepared, radiance, DisplayMode::pixel);
    EXPECT_EQ(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)), 0);
    // The tests' shared room is prepared without per-pixel light.
    EXPECT_TRUE(test::coarseRoom().prepared.pixelDirect.empty());
    EXPECT_THROW(renderEdit(test::coarseRoom().prepared, radiance, DisplayMode::pixel),
                 std::invalid_argument);
}

TEST(PixelLight, TheCornellBoxsVirtualBoxCastsItsShadowPerPixel) {
    // virtual_box: a blue box on the Cornell box's floor under its one ceiling lamp, whose
    // shadow is sharp near the box. The vertex displays interpolate it over leaves that were
    // not refined for it; per pixel its direct light is measured again where the box's
    // shafts cut a light link. Measured at the default settings (bench/RESULTS.md,
    // 2026-11-25): changed_rel_rmse 0.150 (ratio) against 0.112 (pixel), the bounds
    // 0.05 and 0.15. Here, at the default epsilon with the tests' fewer samples and rounds:
    // within the bounds, and a tenth better than the ratio display where the image changes.
    const std::string dir = RELIGHT_DATA_DIR "/cornell";
    RelightOptions o = test::coarseOptions();
    o.epsilon = RelightOptions{}.epsilon;
    o.pixelLight = true;
    const auto run =
        test::renderEditIn(dir, "virtual_box", o, {DisplayMode::ratio, DisplayMode::pixel});
    const Image& photo = run.relighting->prepared.photo;
    const Score sr = test::scoreAgainstTruth(dir, "virtual_box", run.images[0], photo);
    const Score sp = test::scoreAgainstTruth(dir, "virtual_box", run.images[1], photo);
    std::printf("virtual_box: ratio %.4f / %.4f, pixel %.4f / %.4f\n", sr.relRmse,
                sr.changedRelRmse, sp.relRmse, sp.changedRelRmse);
    ASSERT_TRUE(sp.hasChanged);
    EXPECT_LE(sp.relRmse, 0.05);
    EXPECT_LE(sp.changedRelRmse, 0.15);
    EXPECT_LT(sp.changedRelRmse, 0.9 * sr.changedRelRmse);
}

TEST(PixelLight, ABrightenedDimPhotoShowsItsReflectancePooledNotItsNoise) {
    // One light; the photo received 0.1 per pixel (direct, no indirect) and shows two
    // surfaces side by side, reflectance 0.5 (x < 8) and 0.2, with +-10 % noise. Lit 4 times
    // as much, each pixel is w T/H + (1 - w) R_pooled, w = 1.5 / 4: the noise shrinks and
    // the surfaces do not mix (2.5 times apart, beyond the 30 % tolerance).
    const int W = 16, H = 8;
    const DisplayMap map = test::surfaceGrid(W, H);
    Image photo(W, H);
    const auto truthRho = [](int x) { return x < 8 ? 0.5 : 0.2; };
    const auto noise = [](int x, int y) { return ((x * 7 + y * 3) % 5 - 2) * 0.05; };  // +-10 %
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c)
                photo.at(x, y)[c] = static_cast<float>(truthRho(x) * 0.1 * (1 + noise(x, y)));
    const std::vector<float> direct(static_cast<size_t>(W * H), 0.1f);
    const std::vector<Rgb> indirect(static_cast<size_t>(W * H), Rgb{});
    const std::vector<Rgb> inPhoto{Rgb::gray(1.0)};
    const Rgb delta = Rgb::gray(1e-9);
    const PhotoPixels pool = photoPixels(map, photo, direct, indirect, inPhoto, delta);
    ASSERT_EQ(pool.light.size(), static_cast<size_t>(W * H));

    const auto render = [&](double radiance, const PhotoPixels* p) {
        Image out(W, H);
        const std::vector<Rgb> now{Rgb::gray(radiance)};
        renderPixelLight(map, photo, direct, indirect, now, inPhoto, delta, out, {}, {}, p);
        return out;
    };
    const auto spread = [&](const Image& img, bool left) {
        // Relative RMS deviation from the true value 4 x 0.1 x rho, over the interior.
        double sum = 0;
        int n = 0;
        for (int y = 2; y < H - 2; ++y)
            for (int x = left ? 2 : 10; x < (left ? 6 : 14); ++x) {
                const double want = truthRho(x) * 0.4;
                sum += std::pow((static_cast<double>(img.at(x, y)[0]) - want) / want, 2);
                ++n;
            }
        return std::sqrt(sum / n);
    };
    const Image plain = render(4.0, nullptr), pooled = render(4.0, &pool);
    for (bool left : {true, false}) {
        SCOPED_TRACE(left ? "rho 0.5" : "rho 0.2");
        EXPECT_GT(spread(plain, left), 0.06);  // the photo's noise, as it was
        EXPECT_LT(spread(pooled, left), 0.5 * spread(plain, left));
    }
    // No mixing across the edge: every pixel stays within the noise of its own surface.
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double v = static_cast<double>(pooled.at(x, y)[0]), want = truthRho(x) * 0.4;
            EXPECT_NEAR(v, want, 0.101 * want) << x << " " << y;
        }
    // Light kept or dimmed (and brightened up to 1.5 times): the photo's own pixels.
    for (double radiance : {0.5, 1.0, 1.4}) {
        const Image a = render(radiance, nullptr), b = render(radiance, &pool);
        EXPECT_EQ(a.rgb, b.rgb) << radiance;
    }
}

TEST(PixelLight, APooledDimPixelLosesItsNoiseEvenWhenTheNoiseReachesTheTolerance) {
    // One surface of reflectance 0.3 under a photo light of 0.1, each pixel and channel off
    // by a uniform error in [-30 %, 30 %] (standard deviation 17 %: a path-traced photo's
    // dim floor, 17-25 % per pixel in data/window_room), then lit 30 times as much (where a
    // moved sun falls). The pool (w = 1.5 / 30 = 0.05, radius 6 on a grid of step 3: 25
    // pixels) shows, if it keeps every neighbour, 0.05 x 17 % of the pixel's own error and
    // 0.95 x 17 % / 5 of the pool's: 3.4 % per pixel, and no bias. Its test of "the same
    // reflectance" takes the pixel's 3 x 3 median of rho (PhotoPixels::guide, about 7 %
    // off) as the pixel's value, so that nearly every neighbour lies within the 30 %
    // tolerance of it; against the pixel's own rho, the pool kept the neighbours that share
    // the pixel's error. Bounds: 0.05 per pixel (the 3.4 % above, with the neighbours the
    // test still drops where the guide is off), two thirds of the spread with the pixel's
    // own rho as the reference, and the mean within 1.5 % of 0.3 x 3 (the tolerance's
    // window, [0.7, 1/0.7] of the guide, holds the whole +-30 % when the guide is right).
    const int W = 42, H = 42;
    const DisplayMap map = test::surfaceGrid(W, H);
    Image photo(W, H);
    const auto noise = [](int x, int y, int c) {
        uint64_t z = static_cast<uint64_t>((y * W + x) * 3 + c) * 0x9e3779b97f4a7c15ull + 1;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        return 0.6 * (static_cast<double>(z >> 11) / 9007199254740992.0 - 0.5);  // [-0.3, 0.3)
    };
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            for (int c = 0; c < 3; ++c)
                photo.at(x, y)[c] = static_cast<float>(0.3 * 0.1 * (1 + noise(x, y, c)));
    const std::vector<float> direct(static_cast<size_t>(W * H), 0.1f);
    const std::vector<Rgb> indirect(static_cast<size_t>(W * H), Rgb{});
    const std::vector<Rgb> inPhoto{Rgb::gray(1.0)};
    const Rgb delta = Rgb::gray(1e-9);
    PhotoPixels pool = photoPixels(map, photo, direct, indirect, inPhoto, delta);
    ASSERT_EQ(pool.guide.size(), pool.rho.size());
    const auto spreadAndMean = [&](const PhotoPixels& p) {
        Image out(W, H);
        const std::vector<Rgb> now{Rgb::gray(30.0)};
        renderPixelLight(map, photo, direct, indirect, now, inPhoto, delta, out, {}, {}, &p);
        const double want = 0.3 * 3.0;
        double sum = 0, mean = 0;
        int n = 0;
        for (int y = 6; y < H - 6; ++y)
            for (int x = 6; x < W - 6; ++x)
                for (int c = 0; c < 3; ++c) {
                    const double v = static_cast<double>(out.at(x, y)[c]) / want;
                    sum += (v - 1) * (v - 1);
                    mean += v;
                    ++n;
                }
        return std::pair{std::sqrt(sum / n), mean / n};
    };
    const auto [guided, guidedMean] = spreadAndMean(pool);
    pool.guide.clear();  // the pixel's own rho as the reference, as before
    const auto [own, ownMean] = spreadAndMean(pool);
    std::printf("pooled spread per pixel: guided %.4f (mean %.4f), own rho %.4f (mean %.4f)\n",
                guided, guidedMean, own, ownMean);
    EXPECT_LT(guided, 0.05);
    EXPECT_NEAR(guidedMean, 1.0, 0.015);
    EXPECT_LT(guided, 2.0 / 3.0 * own);
}

TEST(PixelLight, ThePhotosIrradianceViewMatchesThePathTracersLight) {
    // The H_photo debug view (display/debug_views.h) is the irradiance the per-pixel display
    // divides the photo by. The path tracer's, implied by its albedo pass (truth, read by
    // the test only), is pi T / albedo. Over the room's surface pixels their ratio has a
    // median within 5 % of 1 (coarse settings, epsilon 1e-3) and 95 % of the
    // pixels within 15 % (measured: 0.991, 99.2 %): a wrong indirect term, unit or
    // interpolation moves the whole
    // distribution. Pixels below a tenth of the photo's mean are left out (their ratio is
    // the path tracer's noise).
    const Relighting& r = pixelRoom();
    const DebugViews v = computeDebugViews(r, r.prepared.photoRadiance);
    ASSERT_EQ(v.Hphoto.width, r.prepared.photo.width);
    const Image albedo = readImage(kRoom + "/truth/albedo.exr");
    const Image& T = r.prepared.photo;
    double mean = 0;
    for (float x : T.rgb) mean += static_cast<double>(x);
    mean /= static_cast<double>(T.rgb.size());
    std::vector<double> ratio;
    for (size_t i = 0; i < T.rgb.size(); ++i) {
        const double h = v.Hphoto.rgb[i], t = T.rgb[i], a = albedo.rgb[i];
        if (!(h > 0) || !(t > 0.1 * mean) || !(a > 0.05)) continue;
        ratio.push_back(h * a / (std::numbers::pi * t));
    }
    ASSERT_GT(ratio.size(), T.rgb.size() / 2);
    std::sort(ratio.begin(), ratio.end());
    const double median = ratio[ratio.size() / 2];
    EXPECT_NEAR(median, 1.0, 0.05);
    const auto within =
        std::count_if(ratio.begin(), ratio.end(), [](double x) { return std::abs(x - 1) < 0.15; });
    EXPECT_GT(static_cast<double>(within), 0.95 * static_cast<double>(ratio.size()))
        << "median " << median;
    std::printf("H_photo / path tracer's: median %.4f, %.1f %% within 15 %%\n", median,
                100.0 * static_cast<double>(within) / static_cast<double>(ratio.size()));
}
