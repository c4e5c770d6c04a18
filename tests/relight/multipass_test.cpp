// Multi-pass display of display ratios above 1 (Loscos et al. 2000, §5.3, Fig. 19): the
// passes sum to T * B/D, and an 8-bit emulation of the fixed-function pipeline stays within
// the 8-bit quantization bound of the float single pass T * B/D clipped to [0, 1].
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "relight/display/multipass.h"

using namespace relight;

namespace {

// The error bound of the 8-bit multi-pass display against t r clipped to [0, 1], for a
// ratio r in [0, kMaxPasses]. In steps of 1/255, with t8 = round(255 t), c_k = round(255
// m_k), m_k = passModulation(r, k), p_k = round(t8 c_k / 255), and sum m_k = r:
//   sum p_k - 255 t r = sum (p_k - t8 c_k / 255)          (a) product roundings
//                     + sum t8 (c_k - 255 m_k) / 255      (b) colour roundings
//                     + (t8 - 255 t) sum m_k              (c) texel rounding
// Passes with m_k = 1 give c_k = 255 and p_k = t8 exactly; passes with m_k = 0 give 0. At
// most one pass has a fractional m_k, so |(a)| <= 1/2 and |(b)| <= (1/2)(t8/255) <= 1/2;
// |(c)| <= r/2 since |t8 - 255 t| <= 1/2. Hence |sum p_k - 255 t r| <= 1 + r/2, and the
// framebuffer's min(255, .) against the reference's min(1, .) cannot make it larger
// (min(c, .) is 1-Lipschitz). The naive "3 roundings of 1/2 per pass" count would give
// 1.5 n + 1/2 steps; the exact full passes make the bound independent of n but for the
// texel term. The last term is slack for the float arithmetic of the reference (t * r in
// float, k / 255 in float: a few 1e-8).
double multipassBound(double r) {
    return (1.0 + 0.5 * r) / 255.0 + 1e-6;
}

double reference(float t, float r) {
    return std::min(1.0, static_cast<double>(std::clamp(t, 0.0f, 1.0f)) * static_cast<double>(r));
}

// Texture values: every 8-bit texel exactly, and a dense off-grid sweep of [0, 1].
std::vector<float> textureSweep() {
    std::vector<float> ts;
    for (int i = 0; i <= 255; ++i) ts.push_back(static_cast<float>(i) / 255.0f);
    for (int j = 0; j <= 1000; ++j) ts.push_back(static_cast<float>(j) / 1000.0f);
    return ts;
}

// Ratios in [0, 8]: a dense grid (r < 1, r = 1, between 1 and 8, the integers), values
// just around each integer, and random ones.
std::vector<float> ratioSweep() {
    std::vector<float> rs;
    for (int j = 0; j <= 8 * 128; ++j) rs.push_back(static_cast<float>(j) / 128.0f);
    for (int k = 1; k <= 8; ++k) {
        const float f = static_cast<float>(k);
        rs.push_back(std::nextafter(f, 0.0f));
        if (k < 8) rs.push_back(std::nextafter(f, 9.0f));
        rs.push_back(f - 0.001f);
        if (k < 8) rs.push_back(f + 0.001f);
    }
    rs.push_back(1.01f);
    rs.push_back(3.5f);
    std::mt19937 rng(20000);
    std::uniform_real_distribution<float> u(0.0f, 8.0f);
    for (int i = 0; i < 500; ++i) rs.push_back(u(rng));
    return rs;
}

}  // namespace

TEST(Multipass, PassCount) {
    EXPECT_EQ(multipassCount(0.3f), 1);
    EXPECT_EQ(multipassCount(0.0f), 1);
    EXPECT_EQ(multipassCount(1.0f), 1);
    EXPECT_EQ(multipassCount(1.01f), 2);
    EXPECT_EQ(multipassCount(2.0f), 2);
    EXPECT_EQ(multipassCount(3.5f), 4);
    EXPECT_EQ(multipassCount(std::numeric_limits<float>::quiet_NaN()), 1);
    EXPECT_EQ(multipassCount(-0.5f), 1);
    EXPECT_EQ(multipassCount(-std::numeric_limits<float>::infinity()), 1);
    // Documented cap: ratios above kMaxPasses, +Inf included, are clamped to kMaxPasses.
    EXPECT_EQ(multipassCount(static_cast<float>(kMaxPasses)), kMaxPasses);
    EXPECT_EQ(multipassCount(1000.0f), kMaxPasses);
    EXPECT_EQ(multipassCount(std::numeric_limits<float>::infinity()), kMaxPasses);
}

TEST(Multipass, ModulationIsTheRatioMinusThePassClampedToZeroOne) {
    EXPECT_EQ(passModulation(2.25f, 0), 1.0f);
    EXPECT_EQ(passModulation(2.25f, 1), 1.0f);
    EXPECT_EQ(passModulation(2.25f, 2), 0.25f);
    EXPECT_EQ(passModulation(2.25f, 3), 0.0f);
    EXPECT_EQ(passModulation(0.6f, 0), 0.6f);
    EXPECT_EQ(passModulation(-1.0f, 0), 0.0f);
    EXPECT_EQ(passModulation(std::numeric_limits<float>::quiet_NaN(), 0), 0.0f);
}

TEST(Multipass, ModulationsSumToTheRatioExactly) {
    for (const float r : ratioSweep()) {
        const int n = multipassCount(r);
        ASSERT_LE(r, static_cast<float>(n));
        float sum = 0.0f;
        for (int k = 0; k < n; ++k) {
            const float m = passModulation(r, k);
            ASSERT_GE(m, 0.0f);
            ASSERT_LE(m, 1.0f);
            sum += m;
        }
        EXPECT_EQ(sum, r) << "n = " << n;
        // Extra passes beyond n add nothing.
        EXPECT_EQ(passModulation(r, n), 0.0f);
    }
    // Every integer ratio up to the cap, and the cap itself.
    for (int k = 0; k <= kMaxPasses; ++k) {
        const float r = static_cast<float>(k) + (k < kMaxPasses ? 0.5f : 0.0f);
        float sum = 0.0f;
        for (int p = 0; p < multipassCount(r); ++p) sum += passModulation(r, p);
        EXPECT_EQ(sum, r);
    }
}

TEST(Multipass, EightBitOperationsRoundLikeFixedFunctionOpenGL) {
    EXPECT_EQ(quantize8(0.0f), 0);
    EXPECT_EQ(quantize8(1.0f), 255);
    EXPECT_EQ(quantize8(2.0f), 255);
    EXPECT_EQ(quantize8(-0.1f), 0);
    EXPECT_EQ(quantize8(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(quantize8(0.5f), 128);  // 127.5 rounds up
    for (int i = 0; i <= 255; ++i) EXPECT_EQ(quantize8(static_cast<float>(i) / 255.0f), i);
    for (int a = 0; a <= 255; ++a)
        for (int b = 0; b <= 255; ++b) {
            const auto ua = static_cast<std::uint8_t>(a), ub = static_cast<std::uint8_t>(b);
            ASSERT_EQ(modulate8(ua, ub), static_cast<int>(std::lround(a * b / 255.0)));
        }
    EXPECT_EQ(modulate8(200, 255), 200);  // a full pass is exact
}

TEST(Multipass, EightBitMultipassMatchesTheFloatSinglePassWithinTheQuantizationBound) {
    double worst = 0, worstRatio = 0;  // largest error, and as a fraction of the bound
    int saturated = 0, above1 = 0;
    for (const float r : ratioSweep()) {
        // |multipass - min(1, t r)| <= (1 + r/2) / 255 (+ float slack); derivation at
        // multipassBound above.
        const double bound = multipassBound(static_cast<double>(r));
        for (const float t : textureSweep()) {
            const double got = static_cast<double>(multipassPixel8(t, r)) / 255.0;
            const double err = std::abs(got - static_cast<double>(singlePassPixel(t, r)));
            ASSERT_LE(err, bound) << "t = " << t << ", r = " << r;
            ASSERT_LE(std::abs(got - reference(t, r)), bound) << "t = " << t << ", r = " << r;
            worst = std::max(worst, err);
            worstRatio = std::max(worstRatio, err / bound);
            if (r > 1.0f) ++above1;
            if (static_cast<double>(t) * static_cast<double>(r) > 1.0) {
                ++saturated;
                EXPECT_GE(got, 1.0 - bound) << "t = " << t << ", r = " << r;
            }
        }
    }
    EXPECT_GT(above1, 0);
    EXPECT_GT(saturated, 0);
    // The bound is not vacuous: the sweep reaches more than half of it.
    EXPECT_GT(worstRatio, 0.5);
    std::printf("[          ] worst error %.3f/255, %.2f of the bound\n", worst * 255.0,
                worstRatio);
}

TEST(Multipass, OneEightBitPassWithoutMultipassClipsTheRatioAtOne) {
    for (const float r : ratioSweep()) {
        for (const float t : textureSweep()) {
            const std::uint8_t single = framebuffer8(t, r, 1);
            if (r <= 1.0f) {
                // One pass is all the multi-pass display draws: identical.
                ASSERT_EQ(single, multipassPixel8(t, r));
                continue;
            }
            // r > 1: glColor clamps the ratio to 1, so the single pass shows the texture
            // unchanged, T * min(B/D, 1), whatever the ratio.
            ASSERT_EQ(single, quantize8(t)) << "t = " << t << ", r = " << r;
            // For mid-grey textures and a clear brightening it misses t r by far more than
            // the multi-pass bound: min(1, t r) - t >= min(1 - t, t (r - 1)) >= 0.05 =
            // 12.75/255 for t in [0.1, 0.9] and r >= 1.5, against (1 + r/2)/255 <= 5/255.
            if (r >= 1.5f && t >= 0.1f && t <= 0.9f) {
                const double singleErr =
                    std::abs(static_cast<double>(single) / 255.0 - reference(t, r));
                const double multiErr =
                    std::abs(static_cast<double>(multipassPixel8(t, r)) / 255.0 - reference(t, r));
                ASSERT_GT(singleErr, multipassBound(static_cast<double>(r)))
                    << "t = " << t << ", r = " << r;
                ASSERT_LT(multiErr, singleErr) << "t = " << t << ", r = " << r;
            }
        }
    }
    // Fig. 20's point in one pixel: a grey texel under a ratio of 2 stays grey in one pass
    // and doubles in two.
    EXPECT_EQ(framebuffer8(0.4f, 2.0f, 1), 102);
    EXPECT_EQ(multipassPixel8(0.4f, 2.0f), 204);
}

TEST(Multipass, RatiosAboveTheCapAreClampedToTheCap) {
    const float inf = std::numeric_limits<float>::infinity();
    const float cap = static_cast<float>(kMaxPasses);
    for (int i = 0; i <= 255; ++i) {
        const float t = static_cast<float>(i) / 255.0f;
        EXPECT_EQ(multipassPixel8(t, 1000.0f), multipassPixel8(t, cap));
        EXPECT_EQ(multipassPixel8(t, inf), multipassPixel8(t, cap));
        EXPECT_EQ(framebuffer8(t, inf, 1000), framebuffer8(t, cap, kMaxPasses));
    }
    EXPECT_EQ(multipassPixel8(0.0f, inf), 0);
    EXPECT_EQ(multipassPixel8(1.0f / 255.0f, inf), kMaxPasses);  // 64 passes of 1 step
    EXPECT_EQ(multipassPixel8(0.5f, std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(multipassPixel8(0.5f, -2.0f), 0);
    EXPECT_EQ(singlePassPixel(0.0f, inf), 0.0f);
    EXPECT_EQ(singlePassPixel(0.5f, inf), 1.0f);
}

TEST(Multipass, WholeImageMatchesTheFloatSinglePassWithinTheBound) {
    // 16x8 synthetic texture; ratio ramp 0..4 across x in the red channel, scaled by 0.75
    // and 0.5 in green and blue.
    const int w = 16, h = 8;
    Image texture(w, h), ratio(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                texture.at(x, y)[c] = static_cast<float>((x * 7 + y * 13 + c * 5) % 32) / 31.0f;
                const float ramp = 4.0f * static_cast<float>(x) / static_cast<float>(w - 1);
                ratio.at(x, y)[c] = ramp * (c == 0 ? 1.0f : c == 1 ? 0.75f : 0.5f);
            }
    int passes = 0;
    const Image got = multipassDisplay8(texture, ratio, &passes);
    const Image want = singlePassFloat(texture, ratio);
    EXPECT_EQ(passes, 4);  // ceil(max ratio) = ceil(4)
    ASSERT_EQ(got.width, w);
    ASSERT_EQ(got.height, h);
    ASSERT_EQ(want.width, w);
    ASSERT_EQ(want.height, h);
    int brightened = 0, saturated = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float t = texture.at(x, y)[c], r = ratio.at(x, y)[c];
                const double g = static_cast<double>(got.at(x, y)[c]);
                // Values are k/255.
                const double k = g * 255.0;
                ASSERT_NEAR(k, std::round(k), 1e-3);
                // Within the per-pixel bound (1 + r/2)/255, derived at multipassBound.
                ASSERT_LE(std::abs(g - static_cast<double>(want.at(x, y)[c])),
                          multipassBound(static_cast<double>(r)))
                    << "x = " << x << ", y = " << y << ", c = " << c;
                ASSERT_EQ(want.at(x, y)[c], singlePassPixel(t, r));
                // The image's 4 passes give each pixel what its own pass count gives: the
                // extra passes add nothing.
                ASSERT_EQ(std::lround(k), multipassPixel8(t, r));
                if (r > 1.0f && g > static_cast<double>(t) + 2.0 / 255.0) ++brightened;
                if (g == 1.0 && static_cast<double>(t) * static_cast<double>(r) > 1.0) ++saturated;
            }
    EXPECT_GT(brightened, 0);
    EXPECT_GT(saturated, 0);

    // The grey-ratio overload: one ratio per pixel, ramp 0..3.2 over the pixels.
    std::vector<float> grey(static_cast<size_t>(w) * h);
    for (size_t i = 0; i < grey.size(); ++i)
        grey[i] = 3.2f * static_cast<float>(i) / static_cast<float>(grey.size() - 1);
    const Image gotGrey = multipassDisplay8(texture, grey, &passes);
    const Image wantGrey = singlePassFloat(texture, grey);
    EXPECT_EQ(passes, 4);  // ceil(3.2)
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) {
                const float r = grey[static_cast<size_t>(y) * w + static_cast<size_t>(x)];
                ASSERT_LE(std::abs(static_cast<double>(gotGrey.at(x, y)[c]) -
                                   static_cast<double>(wantGrey.at(x, y)[c])),
                          multipassBound(static_cast<double>(r)));
            }
}

TEST(Multipass, WholeImagePassCountEdgeCases) {
    Image texture(2, 1), ratio(2, 1);
    std::fill(texture.rgb.begin(), texture.rgb.end(), 0.5f);
    // All ratios <= 1: one pass; a NaN ratio is ignored for the count and shows black.
    ratio.rgb = {0.5f, 1.0f, 0.25f, std::numeric_limits<float>::quiet_NaN(), 0.0f, -1.0f};
    int passes = 0;
    Image got = multipassDisplay8(texture, ratio, &passes);
    EXPECT_EQ(passes, 1);
    EXPECT_EQ(got.at(1, 0)[0], 0.0f);
    EXPECT_EQ(got.at(1, 0)[2], 0.0f);
    EXPECT_EQ(got.at(0, 0)[1], 128.0f / 255.0f);
    // Without the out-parameter.
    got = multipassDisplay8(texture, ratio);
    EXPECT_EQ(got.width, 2);
    // An empty image draws one (empty) pass.
    got = multipassDisplay8(Image(), Image(), &passes);
    EXPECT_EQ(passes, 1);
    EXPECT_TRUE(got.rgb.empty());
}

TEST(Multipass, WholeImageRejectsMismatchedSizes) {
    const Image texture(4, 2);
    EXPECT_THROW(multipassDisplay8(texture, Image(2, 4)), std::invalid_argument);
    EXPECT_THROW(singlePassFloat(texture, Image(4, 3)), std::invalid_argument);
    EXPECT_THROW(multipassDisplay8(texture, std::vector<float>(7)), std::invalid_argument);
    EXPECT_THROW(singlePassFloat(texture, std::vector<float>(24)), std::invalid_argument);
    EXPECT_NO_THROW(multipassDisplay8(texture, std::vector<float>(8)));
}
