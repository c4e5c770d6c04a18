// The confidence display (relight/pipeline/confidence.h, relight/prepared.h): the photo's
// confidence per vertex, the split of an edit's light into the photo's lamps and fresh
// light, the display values, the added term of the display, and the Cornell box's virtual
// lamp against the path-traced truth.
#include "relight/pipeline/confidence.h"

#include <gtest/gtest.h>

#include <numbers>

#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;
using radiosity::Rgb;

namespace {

/// Direct light of `n` vertices and two lamps, every vertex seeing `visible` of lamp 0's
/// unoccluded 0.1 and all of lamp 1's 0.2.
VertexDirect twoLamps(const std::vector<double>& visible0, double lamp1 = 0.2) {
    VertexDirect d;
    d.lights = 2;
    for (const double v : visible0) {
        d.visible.insert(d.visible.end(), {0.1 * v, lamp1});
        d.unoccluded.insert(d.unoccluded.end(), {0.1, lamp1});
    }
    return d;
}

}  // namespace

TEST(VertexConfidence, IsTheRampOfThePhotosLampVisibility) {
    // Lamp 1 is off in the photo, so only lamp 0 counts: V is the visible share of lamp 0.
    // K = (V - 0.2) / (0.7 - 0.2) clamped: V 1 -> 1, 0.7 -> 1, 0.45 -> 0.5, 0.2 -> 0, 0 -> 0.
    const std::vector<Rgb> photo = {Rgb{3, 2, 1}, Rgb{}};
    const std::vector<float> K = vertexConfidence(twoLamps({1, 0.7, 0.45, 0.2, 0}), photo);
    ASSERT_EQ(K.size(), 5u);
    EXPECT_FLOAT_EQ(K[0], 1.0f);
    EXPECT_FLOAT_EQ(K[1], 1.0f);
    EXPECT_NEAR(K[2], 0.5f, 1e-6);
    EXPECT_FLOAT_EQ(K[3], 0.0f);
    EXPECT_FLOAT_EQ(K[4], 0.0f);
    // Both lamps on: V weighs each by its radiance (brightest channel, 3 and 1) and G. A
    // vertex that sees none of lamp 0 (unoccluded 3 x 0.1) and all of lamp 1 (1 x 0.2):
    // V = 0.2 / 0.5 = 0.4, K = (0.4 - 0.2) / 0.5 = 0.4.
    const std::vector<float> both =
        vertexConfidence(twoLamps({0}), std::vector<Rgb>{Rgb{3, 2, 1}, Rgb{1, 1, 1}});
    EXPECT_NEAR(both[0], 0.4f, 1e-6);
    // No lamp of the photo faces the vertex: indirect light only, K = 0.
    EXPECT_FLOAT_EQ(vertexConfidence(twoLamps({0}, 0.0), std::vector<Rgb>{Rgb{}, Rgb{1, 1, 1}})[0],
                    0.0f);
    EXPECT_THROW(vertexConfidence(twoLamps({1}), std::vector<Rgb>{Rgb{1, 1, 1}}),
                 std::invalid_argument);
}

TEST(VertexDisplay, WeighsFreshLightByConfidence) {
    // Two vertices with D = 2, no texture factor; K = 1 and 0; model reflectance 0.5.
    PreparedImage p;
    p.D = {Rgb::gray(2), Rgb::gray(2)};
    p.textureFactor = {Rgb::gray(1), Rgb::gray(1)};
    p.confidence = {1.0f, 0.0f};
    p.modelReflectance = {Rgb::gray(0.5), Rgb::gray(0.5)};
    SplitIrradiance H;
    H.kept = {Rgb::gray(1), Rgb::gray(1)};
    H.fresh = {Rgb::gray(4), Rgb::gray(4)};
    const VertexDisplay c = vertexDisplay(p, H, DisplayMode::confidence);
    const VertexDisplay r = vertexDisplay(p, H, DisplayMode::ratio);
    // Ratio display: (1 + 4) / 2 at both (to the display's floor, 1e-4 relative).
    EXPECT_NEAR(r.ratio[1].r, 2.5, 1e-3);
    EXPECT_TRUE(r.added.empty());
    // K = 1: the ratio display. K = 0: the photo's lamps by the ratio, the fresh light as
    // the model's radiance rho H / pi.
    EXPECT_NEAR(c.ratio[0].r, 2.5, 1e-3);
    EXPECT_DOUBLE_EQ(c.added[0].r, 0.0);
    EXPECT_NEAR(c.ratio[1].r, 0.5, 1e-3);
    EXPECT_DOUBLE_EQ(c.added[1].g, 0.5 * 4 / std::numbers::pi);
    // No fresh light (an edit of the photo's own lamps): the ratio display, bit for bit.
    H.fresh = {Rgb{}, Rgb{}};
    const VertexDisplay same = vertexDisplay(p, H, DisplayMode::confidence);
    EXPECT_TRUE(same.added.empty());
    EXPECT_EQ(same.ratio, vertexRatio(p, H.kept));
    // The per-pixel display has no vertex values (virtual parts cannot use it yet).
    EXPECT_THROW(vertexDisplay(p, H, DisplayMode::pixel), std::invalid_argument);
}

TEST(RenderRatio, AddedRadianceIsInterpolatedAndClampedWithTheRest) {
    // Two pixels of one vertex each (general arrays), then the same map packed in runs.
    DisplayMap m;
    m.width = 2;
    m.height = 1;
    m.start = {0, 1, 2};
    m.vertex = {0, 1};
    m.weight = {1.0f, 1.0f};
    m.unshaded = {0, 0};
    m.emitterStart = {0, 0, 0};
    Image photo(2, 1);
    for (float& v : photo.rgb) v = 0.5f;
    const std::vector<Rgb> ratio = {Rgb::gray(2), Rgb::gray(1)};
    const std::vector<Rgb> added = {Rgb{0.25, 0, -0.25}, Rgb::gray(-2)};
    for (const bool packed : {false, true}) {
        DisplayMap map = m;
        if (packed) packDisplayMap(map);
        Image out;
        renderRatio(map, photo, ratio, {}, {}, out, added);
        EXPECT_FLOAT_EQ(out.at(0, 0)[0], 1.25f) << packed;  // 0.5 * 2 + 0.25
        EXPECT_FLOAT_EQ(out.at(0, 0)[2], 0.75f) << packed;  // 0.5 * 2 - 0.25
        EXPECT_FLOAT_EQ(out.at(1, 0)[1], 0.0f) << packed;   // 0.5 - 2, clamped at 0
    }
    Image out;
    EXPECT_THROW(renderRatio(m, photo, ratio, {}, {}, out, std::vector<Rgb>{Rgb{}}),
                 std::invalid_argument);
}

TEST(ConfidenceDisplay, TheCornellBoxsVirtualLampNearerTheTruthThanTheRatio) {
    // The Cornell box's virtual_light_only: the ceiling lamp off, a lamp on the red wall.
    // The blocks' faces that the ceiling lamp did not light are where the ratio display
    // multiplies the photo by the model's least certain D. Measured at the default
    // settings: 0.092 (ratio, its map weighed by the photo's radiance) against 0.087
    // (confidence; bench/RESULTS.md, 2026-11-25); at the default epsilon with the tests' fewer
    // samples and rounds, 0.128 against 0.099. The confidence display must gain a fifth on
    // the ratio display there and stay within 0.11 of the truth (the bound is 0.05:
    // not met yet).
    const std::string dir = RELIGHT_DATA_DIR "/cornell";
    RelightOptions o = test::coarseOptions();
    o.epsilon = RelightOptions{}.epsilon;
    const auto run = test::renderEditIn(dir, "virtual_light_only", o,
                                        {DisplayMode::ratio, DisplayMode::confidence});
    const Image& photo = run.relighting->prepared.photo;
    const Score sr = test::scoreAgainstTruth(dir, "virtual_light_only", run.images[0], photo);
    const Score sc = test::scoreAgainstTruth(dir, "virtual_light_only", run.images[1], photo);
    std::printf("virtual_light_only: ratio %.4f, confidence %.4f\n", sr.relRmse, sc.relRmse);
    EXPECT_LT(sc.relRmse, 0.8 * sr.relRmse);
    EXPECT_LT(sc.relRmse, 0.11);
}
