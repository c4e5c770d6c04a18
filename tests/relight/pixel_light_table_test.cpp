// The per-pixel light edit's fast path (relight/pipeline/pixel_light_table.h) against the
// general path it replaces (renderPixelEditReference: renderRatio, then renderPixelLight in
// double), on the room with its own light edits, lamps switched off, brightened until the
// pooled reflectance takes over, and coloured.
#include "relight/pipeline/pixel_light_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "relight/io/edit_file.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;
using radiosity::Rgb;

namespace {

const std::string kRoom = RELIGHT_DATA_DIR "/room";

/// The room prepared with per-pixel light, shared by the test files (room_fixture.h).
const Relighting& pixelRoom() {
    return test::coarsePixelRoom();
}

/// The edits compared: the room's light edits, then random scalings in [0, 3] of each lamp
/// and channel (a third of the pixels or more brightened past kPoolAbove: the pooled path).
std::vector<std::vector<Rgb>> edits(const Relighting& r) {
    std::vector<std::vector<Rgb>> out;
    for (const char* name :
         {"back_off", "left_off_right_double", "right_off_left_double", "colours"})
        out.push_back(editRadiance(r.scene, loadEdit(kRoom + "/edits/" + name + ".json", r.scene),
                                   r.prepared.photoRadiance));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> scale(0.0, 3.0);
    for (int k = 0; k < 6; ++k) {
        std::vector<Rgb> L = r.prepared.photoRadiance;
        for (auto& l : L)
            for (int c = 0; c < 3; ++c) l[c] *= scale(rng);
        out.push_back(L);
    }
    return out;
}

}  // namespace

TEST(PixelLightTable, TheFastPathEqualsTheReferenceToFloatRounding) {
    const PreparedImage& p = pixelRoom().prepared;
    ASSERT_FALSE(p.pixelTable.empty());
    ASSERT_TRUE(p.pixelReflectance.empty());  // one photo: renderEdit takes the fast path
    const size_t pixels = p.pixelTable.pixels;
    ASSERT_GT(p.pixelTable.ratioPixels.size(), 0u);  // the lamps' faces: the ratio part runs
    int pooled = 0;
    for (const auto& L : edits(pixelRoom())) {
        Image fast, ref;
        renderEdit(p, L, fast, DisplayMode::pixel);
        renderPixelEditReference(p, L, ref);
        ASSERT_EQ(fast.rgb.size(), ref.rgb.size());
        // Each of the pixels the ratio display draws comes from the same float arithmetic
        // on the same per-vertex ratios (ratioPixel()): equal bit for bit.
        for (const int px : p.pixelTable.ratioPixels)
            for (size_t c = 0; c < 3; ++c)
                EXPECT_EQ(fast.rgb[3 * static_cast<size_t>(px) + c],
                          ref.rgb[3 * static_cast<size_t>(px) + c]);
        // Elsewhere the fast path sums <= 4 non-negative products in float (each rounded
        // by 2^-24 relative, the sum by at most 4 2^-24 of itself) where the reference sums
        // in double, and multiplies by T / (H_photo + delta) rounded to float once (one
        // more 2^-24, and 2^-24 for the product): about 7 2^-24 = 4e-7 relative; the pooled
        // pixels read the same pool with w from float sums, again a few 1e-7. The bound
        // 2e-6 relative (with 1e-7 of the image's brightest value absolute, for values
        // near 0) leaves a factor of 5 for the stored h_l, itself a double rounded to float.
        float peak = 0;
        for (const float v : ref.rgb) peak = std::max(peak, v);
        double worst = 0;
        for (size_t i = 0; i < 3 * pixels; ++i) {
            const double tol =
                2e-6 * std::abs(static_cast<double>(ref.rgb[i])) + 1e-7 * static_cast<double>(peak);
            worst = std::max(worst, std::abs(static_cast<double>(fast.rgb[i] - ref.rgb[i])) / tol);
        }
        EXPECT_LE(worst, 1.0);
        // Pixels the pooled reflectance draws (pixel_light.h): brightened past kPoolAbove.
        for (size_t px = 0; px < pixels; ++px) {
            Rgb now;
            for (size_t l = 0; l < L.size(); ++l)
                for (int c = 0; c < 3; ++c)
                    now[c] += L[l][c] *
                              static_cast<double>(
                                  p.pixelTable.h[(l * 3 + static_cast<size_t>(c)) * pixels + px]);
            const double light = static_cast<double>(p.pixelTable.photoLight[px]);
            pooled += light > 0 && now.luminance() > kPoolAbove * light;
        }
    }
    EXPECT_GT(pooled, 1000);  // the pooled path is compared too
}

TEST(PixelLightTable, ThePhotosOwnLightIsThePhotoBitForBitOnTheFastPath) {
    // The ratio is exactly 1 at every pixel the per-pixel display draws: T itself.
    const PreparedImage& p = pixelRoom().prepared;
    ASSERT_FALSE(p.pixelTable.empty());
    Image out;
    renderEdit(p, p.photoRadiance, out, DisplayMode::pixel);
    int drawn = 0;
    for (size_t px = 0; px < p.pixelTable.pixels; ++px) {
        if (!shownPerPixel(p.display, px)) continue;
        ++drawn;
        for (size_t c = 0; c < 3; ++c)
            ASSERT_EQ(out.rgb[3 * px + c], std::max(p.photo.rgb[3 * px + c], 0.0f));
    }
    EXPECT_GT(drawn, static_cast<int>(p.pixelTable.pixels / 2));
}
