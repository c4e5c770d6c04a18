// Texture filling (relight/pipeline/texture_fill.h): a hole in a structured texture is filled
// so that the structure goes on through it, each surface from its own samples only.
#include "relight/pipeline/texture_fill.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

using namespace relight;

namespace {

struct Canvas {
    int width, height;
    std::vector<float> value;
    std::vector<int> region;
    std::vector<FillRole> role;
    Canvas(int w, int h)
        : width(w),
          height(h),
          value(static_cast<size_t>(3 * w * h), 0.0f),
          region(static_cast<size_t>(w * h), 0),
          role(static_cast<size_t>(w * h), FillRole::source) {}
    size_t at(int x, int y) const { return static_cast<size_t>(y * width + x); }
    void set(int x, int y, float v) {
        for (int c = 0; c < 3; ++c) value[3 * at(x, y) + c] = v;
    }
    TextureFillInput input() const { return {width, height, value, region, role}; }
};

/// Boards: vertical stripes 3 pixels wide, dark and light, with a step of brightness every
/// 11 rows inside each board (the joints), so that no two offsets look alike locally.
float boards(int x, int y) {
    const bool light = (x / 3) % 2 == 1;
    return (light ? 0.6f : 0.2f) + ((y + 4 * (x / 3)) % 11 == 0 ? 0.1f : 0.0f);
}

}  // namespace

TEST(TextureFill, AStructuredTextureGoesOnThroughTheHole) {
    Canvas c(64, 48);
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) c.set(x, y, boards(x, y));
    // A 14 x 12 hole in the middle, its values wiped.
    for (int y = 18; y < 30; ++y)
        for (int x = 25; x < 39; ++x) {
            c.role[c.at(x, y)] = FillRole::fill;
            c.set(x, y, -1.0f);
        }
    const TextureFillResult r = fillTexture(c.input());
    EXPECT_EQ(r.filled, 14 * 12);
    EXPECT_EQ(r.withoutSource, 0);
    // The stripes carry on: the filled pixel is dark or light as its column is. The texture
    // is periodic in x with period 6 and every source window is copied whole, so matching
    // neighbourhoods put a copy in phase; a few pixels where two copies meet may differ.
    int right = 0;
    for (int y = 18; y < 30; ++y)
        for (int x = 25; x < 39; ++x) {
            const float v = r.value[3 * c.at(x, y)];
            const bool light = v > 0.4f, expected = (x / 3) % 2 == 1;
            right += light == expected ? 1 : 0;
            EXPECT_GE(v, 0.2f);  // a value of the texture, never the wiped one
        }
    EXPECT_GE(right, 14 * 12 * 95 / 100);
    // The sources are left as they were.
    EXPECT_EQ(r.value[3 * c.at(0, 0)], boards(0, 0));
}

TEST(TextureFill, EachSurfaceIsFilledFromItsOwnSamples) {
    Canvas c(40, 20);
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) {
            const bool wall = x < 20;
            c.region[c.at(x, y)] = wall ? 7 : 3;
            c.set(x, y, wall ? 0.7f : 0.25f + 0.05f * static_cast<float>((x + y) % 2));
        }
    for (int y = 5; y < 15; ++y)
        for (int x = 12; x < 28; ++x) c.role[c.at(x, y)] = FillRole::fill;
    const TextureFillResult r = fillTexture(c.input());
    for (int y = 5; y < 15; ++y)
        for (int x = 12; x < 28; ++x) {
            const float v = r.value[3 * c.at(x, y)];
            if (x < 20)
                EXPECT_EQ(v, 0.7f) << x << " " << y;
            else
                EXPECT_TRUE(v == 0.25f || v == 0.3f) << x << " " << y << " " << v;
        }
}

TEST(TextureFill, ASurfaceWithoutSamplesIsReportedUnfilled) {
    Canvas c(10, 10);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) c.set(x, y, 0.5f);
    c.region[c.at(4, 4)] = 9;  // a surface seen nowhere else
    c.role[c.at(4, 4)] = FillRole::fill;
    c.role[c.at(5, 5)] = FillRole::fill;
    const TextureFillResult r = fillTexture(c.input());
    EXPECT_EQ(r.filled, 1);
    EXPECT_EQ(r.withoutSource, 1);
    EXPECT_EQ(r.unfilled[c.at(4, 4)], 1);
    EXPECT_EQ(r.unfilled[c.at(5, 5)], 0);
    EXPECT_EQ(r.value[3 * c.at(5, 5)], 0.5f);
}

TEST(TextureFill, MismatchedSizesAreRefused) {
    Canvas c(4, 4);
    TextureFillInput in = c.input();
    in.width = 5;
    EXPECT_THROW(fillTexture(in), std::invalid_argument);
}

TEST(TextureFill, BlocksCopyWholeBlocksOfTheSample) {
    // The boards at twice the scale (each pixel of AStructuredTextureGoesOnThroughTheHole a
    // 2 x 2 block), filled with blocks of 2: the same structure, and every filled value one of
    // the texture's (copied, never averaged, where the copied pixel is a source).
    Canvas c(128, 96);
    for (int y = 0; y < c.height; ++y)
        for (int x = 0; x < c.width; ++x) c.set(x, y, boards(x / 2, y / 2));
    for (int y = 36; y < 60; ++y)
        for (int x = 50; x < 78; ++x) {
            c.role[c.at(x, y)] = FillRole::fill;
            c.set(x, y, -1.0f);
        }
    TextureFillOptions o;
    o.block = 2;
    const TextureFillResult r = fillTexture(c.input(), o);
    EXPECT_EQ(r.filled, 28 * 24);
    int right = 0;
    for (int y = 36; y < 60; ++y)
        for (int x = 50; x < 78; ++x) {
            const float v = r.value[3 * c.at(x, y)];
            right += (v > 0.4f) == ((x / 6) % 2 == 1) ? 1 : 0;
            EXPECT_TRUE(v == 0.2f || v == 0.2f + 0.1f || v == 0.6f || v == 0.6f + 0.1f)
                << x << " " << y << " " << v;
        }
    EXPECT_GE(right, 28 * 24 * 95 / 100);
    EXPECT_EQ(defaultFillBlock(320, 240), 1);
    EXPECT_EQ(defaultFillBlock(4000, 3000), 6);
}
