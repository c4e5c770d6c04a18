// Reflectance merged from several photos per pixel (relight/pipeline/photo_merge.h): the
// confidence-weighed mean of the photos' readings with the paper's filters, on a map built by
// hand; on room-multi, the photo's own lighting given back exactly and a lamp photographed
// alone nearer the truth than with the first photo alone.
#include "relight/pipeline/photo_merge.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "relight/display/metric.h"
#include "relight/io/edit_file.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;
using radiosity::Rgb;

namespace {

/// A row of `n` surface pixels, pixel x on vertex x alone (weight 1).
DisplayMap row(int n) {
    return test::surfaceGrid(n, 1);
}

Image filled(int n, float v) {
    Image img(n, 1);
    for (float& c : img.rgb) c = v;
    return img;
}

}  // namespace

TEST(PhotoMerge, WeighsEachPhotosReadingByItsDirectLight) {
    // Two lights, one per photo; no indirect light. Pixel x gets pi Gbar = 1 from light 0 and
    // 3 from light 1, both at radiance 1 where on. Photo 0 (light 0) reads T/H = 0.2/1,
    // photo 1 (light 1) reads 0.9/3 = 0.3. K = E (E/H) = E with no indirect part: 1 and 3,
    // so R = (1 * 0.2 + 3 * 0.3) / 4 = 0.275.
    const int n = 4;
    const DisplayMap m = row(n);
    std::vector<float> direct;
    for (int x = 0; x < n; ++x) direct.insert(direct.end(), {1.0f, 3.0f});
    const std::vector<Rgb> indirect(static_cast<size_t>(n) * 2);
    const Image t0 = filled(n, 0.2f), t1 = filled(n, 0.9f);
    std::vector<MergePhoto> photos(2);
    photos[0] = {&t0, {Rgb::gray(1), Rgb{}}};
    photos[1] = {&t1, {Rgb{}, Rgb::gray(1)}};
    const Rgb delta = Rgb::gray(1e-12);
    const PhotoMerge merged = mergePhotos(m, photos, direct, indirect, delta);
    ASSERT_EQ(merged.reflectance.size(), static_cast<size_t>(n) * 3);
    EXPECT_EQ(merged.pixels, n);
    for (const float r : merged.reflectance) EXPECT_NEAR(r, 0.275f, 1e-6f);
    EXPECT_NEAR(merged.firstPhotoShare, 0.25, 1e-9);

    // Pixel value: a NaN in photo 1 at pixel 2 leaves photo 0's reading there.
    Image bad = t1;
    bad.at(2, 0)[1] = std::numeric_limits<float>::quiet_NaN();
    photos[1].image = &bad;
    const PhotoMerge withNaN = mergePhotos(m, photos, direct, indirect, delta);
    EXPECT_NEAR(withNaN.reflectance[2 * 3 + 1], 0.2f, 1e-6f);
    EXPECT_NEAR(withNaN.reflectance[1 * 3 + 1], 0.275f, 1e-6f);
    photos[1].image = &t1;

    // Shadow boundary: light 1's direct light drops to a fifth from pixel 2 on; pixels 1
    // and 2 (each beside the edge) take photo 0's reading alone, the others both.
    std::vector<float> edge = direct;
    for (int x = 2; x < n; ++x) edge[static_cast<size_t>(x) * 2 + 1] = 0.6f;
    const Image t1edge = [&] {
        Image img = t1;
        for (int x = 2; x < n; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, 0)[c] = 0.18f;  // reads 0.3 again
        return img;
    }();
    photos[1].image = &t1edge;
    const PhotoMerge atEdge = mergePhotos(m, photos, edge, indirect, delta);
    EXPECT_NEAR(atEdge.reflectance[0], 0.275f, 1e-6f);
    EXPECT_NEAR(atEdge.reflectance[1 * 3], 0.2f, 1e-6f);
    EXPECT_NEAR(atEdge.reflectance[2 * 3], 0.2f, 1e-6f);
    EXPECT_NEAR(atEdge.reflectance[3 * 3], (0.2f + 0.6f * 0.3f) / 1.6f, 1e-6f);

    // Sizes that do not match are refused.
    EXPECT_THROW(mergePhotos(m, photos, std::vector<float>(3), indirect, delta),
                 std::invalid_argument);
}

TEST(PhotoMerge, OnRoomMultiTheLampPhotographedAloneIsNearerTheTruth) {
    // lamp_M3_on adds lamp M3, which photo_M3 shows alone: read with the merged reflectance
    // its light is the photo's own. Measured at the default settings (bench/RESULTS.md,
    // 2026-11-25): 0.0158 with the first photo alone, 0.0121 merged. Here at the tests'
    // coarse settings: merged below the first photo alone, and within the bound.
    const std::string dir = RELIGHT_DATA_DIR "/room-multi";
    RelightOptions o = test::coarseOptions();
    o.pixelLight = true;
    const auto first = prepareRelighting(loadScene(dir), o);
    o.mergePhotos = true;
    const auto all = prepareRelighting(loadScene(dir), o);
    ASSERT_TRUE(first->prepared.pixelReflectance.empty());
    ASSERT_EQ(all->prepared.pixelReflectance.size(),
              static_cast<size_t>(all->prepared.photo.width) * all->prepared.photo.height * 3);
    // The photo's own lighting: the photo, bit for bit, whatever the merge.
    const Image same = renderEdit(all->prepared, all->prepared.photoRadiance, DisplayMode::pixel);
    const Image unedited =
        renderEdit(first->prepared, first->prepared.photoRadiance, DisplayMode::pixel);
    EXPECT_EQ(same.rgb, unedited.rgb);

    const EditFile e = loadEdit(dir + "/edits/lamp_M3_on.json", all->scene);
    const auto radiance = editRadiance(all->scene, e, all->prepared.photoRadiance);
    const Score sFirst = test::scoreAgainstTruth(
        dir, "lamp_M3_on", renderEdit(first->prepared, radiance, DisplayMode::pixel),
        first->prepared.photo);
    const Score sAll = test::scoreAgainstTruth(
        dir, "lamp_M3_on", renderEdit(all->prepared, radiance, DisplayMode::pixel),
        all->prepared.photo);
    std::printf("lamp_M3_on: first photo %.4f, all photos %.4f\n", sFirst.relRmse, sAll.relRmse);
    EXPECT_LT(sAll.relRmse, sFirst.relRmse);
    EXPECT_LE(sAll.relRmse, 0.05);
}
