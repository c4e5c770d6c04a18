// The ratio map of ../shared/seeds/000 (Eq. 3: L_r = L_o I_r / I_o, I the lights' direct
// irradiance per pixel; `relight render --display ratio-map`) on the room with its light
// edits: the photo's own light gives the photo back, and an edit scales each pixel by the
// ratio of the direct light of the lights alone, computed here from the per-pixel form
// factors (pixelDirect), with no indirect part, unlike the default per-pixel display.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "relight/display/ratio_display.h"
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

/// sum_l L_l pi Gbar_l(p) + delta in channel c: the direct irradiance the ratio map divides.
double directLight(const PreparedImage& p, std::span<const Rgb> L, size_t px, int c) {
    const size_t n = p.photoRadiance.size();
    double h = ratioFloor(p.D)[c];
    for (size_t l = 0; l < n; ++l) h += L[l][c] * static_cast<double>(p.pixelDirect[px * n + l]);
    return h;
}

}  // namespace

TEST(RatioMap, ThePhotosOwnLightIsThePhoto) {
    const PreparedImage& p = pixelRoom().prepared;
    Image out;
    renderEdit(p, p.photoRadiance, out, DisplayMode::ratioMap);
    int drawn = 0;
    for (size_t px = 0; px < p.photo.rgb.size() / 3; ++px) {
        if (!shownPerPixel(p.display, px)) continue;
        ++drawn;
        // I_r / I_o is 1 in double; 1e-6 relative is float rounding of the stored pixel.
        for (size_t c = 0; c < 3; ++c) {
            const float photo = std::max(p.photo.rgb[3 * px + c], 0.0f);
            ASSERT_NEAR(out.rgb[3 * px + c], photo, 1e-6 * static_cast<double>(photo) + 1e-12);
        }
    }
    EXPECT_GT(drawn, static_cast<int>(p.photo.rgb.size() / 6));
}

TEST(RatioMap, AnEditScalesThePhotoByTheDirectLightsRatioAlone) {
    const Relighting& r = pixelRoom();
    const PreparedImage& p = r.prepared;
    const auto L =
        editRadiance(r.scene, loadEdit(kRoom + "/edits/back_off.json", r.scene), p.photoRadiance);
    Image map, pixel;
    renderEdit(p, L, map, DisplayMode::ratioMap);
    renderEdit(p, L, pixel, DisplayMode::pixel);
    double differs = 0;
    int drawn = 0;
    for (size_t px = 0; px < p.photo.rgb.size() / 3; ++px) {
        if (!shownPerPixel(p.display, px)) continue;
        ++drawn;
        for (int c = 0; c < 3; ++c) {
            const size_t i = 3 * px + static_cast<size_t>(c);
            const double photo = static_cast<double>(std::max(p.photo.rgb[i], 0.0f));
            const double want =
                photo * directLight(p, L, px, c) / directLight(p, p.photoRadiance, px, c);
            // Float storage of the pixel and of pi Gbar: 1e-5 relative.
            ASSERT_NEAR(map.rgb[i], want, 1e-5 * want + 1e-9) << "pixel " << px;
            differs += static_cast<double>(std::abs(map.rgb[i] - pixel.rgb[i]));
        }
    }
    EXPECT_GT(drawn, static_cast<int>(p.photo.rgb.size() / 6));
    // The room's indirect light is a large share where the back lamp goes off: the ratio
    // map (no indirect) must differ from the default display there.
    EXPECT_GT(differs, 0.0);
}
