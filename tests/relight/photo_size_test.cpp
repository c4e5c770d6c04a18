// What keeps the preparation and the edit cheap on large photos: the sampling plan (fewer
// samples per pixel, the estimates on a sub-grid of pixels), the lighting buffer on that
// sub-grid, the display map built in parallel and packed into leaf runs. Each must give
// what the plain path gives, and the same with any number of threads.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "relight/display/metric.h"
#include "relight/display/ratio_display.h"
#include "relight/pipeline/lighting_buffer.h"
#include "room_fixture.h"

using namespace relight;
using radiosity::Rgb;

namespace {

const std::string kRoom = RELIGHT_DATA_DIR "/room";

bool sameBits(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height &&
           std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

std::vector<Rgb> radianceOf(const Relighting& r, const std::string& edit) {
    return editRadiance(r.scene, loadEdit(kRoom + "/edits/" + edit + ".json", r.scene),
                        r.prepared.photoRadiance);
}

}  // namespace

TEST(SamplingPlan, KeepsTheRoomsSampleDensityAndStridesTheEstimatesOnLargePhotos) {
    const int64_t b = kDefaultSampleBudget;  // 16 x 320 x 240
    auto plan = [&](int w, int h, int spp, int64_t budget) {
        const SamplingPlan p = planSampling(w, h, spp, budget);
        return std::pair{p.spp, p.stride};
    };
    EXPECT_EQ(plan(320, 240, 16, b), std::pair(16, 1));  // the bundled room: unchanged
    EXPECT_EQ(plan(640, 480, 16, b), std::pair(4, 1));
    EXPECT_EQ(plan(1280, 960, 16, b), std::pair(1, 1));  // exactly the budget
    // 12 MP: 1 sample per pixel; stride 3 would leave 1334 x 1000 > budget samples.
    EXPECT_EQ(plan(4000, 3000, 16, b), std::pair(1, 4));
    EXPECT_EQ(plan(320, 240, 10, b), std::pair(9, 1));      // a square, as castItemBuffer
    EXPECT_EQ(plan(4000, 3000, 16, 0), std::pair(16, 1));   // no budget: as asked
    EXPECT_EQ(plan(320, 240, 16, 19200), std::pair(1, 2));  // 160 x 120 = 19200
    EXPECT_EQ(plan(321, 241, 16, 19200), std::pair(1, 3));  // 161 x 121 > 19200
}

TEST(LightingBuffer, SubGridSamplesAreThoseOfTheFullBuffer) {
    // The direct light of a sample is seeded by its item-buffer index, so the stride only
    // picks samples: the same rays, the same G bit for bit, the same gather positions.
    const Relighting& r = test::coarseRoom();
    const LightingBuffer full = computeLightingBuffer(r.items, *r.solver, {}, 1);
    const LightingBuffer sub = computeLightingBuffer(r.items, *r.solver, {}, 3);
    ASSERT_EQ(sub.stride, 3);
    int compared = 0;
    for (int y = 0; y < r.items.height; y += 3)
        for (int x = 0; x < r.items.width; x += 3)
            for (int k = 0; k < r.items.spp; ++k) {
                const int idx = r.items.sampleIndex(x, y, k);
                ASSERT_GE(sub.slot(idx), 0);
                for (int l = 0; l < full.lights; ++l)
                    ASSERT_EQ(full.direct(idx)[l], sub.direct(idx)[l]) << x << "," << y;
                const int gf = full.gatherPointOf(idx), gs = sub.gatherPointOf(idx);
                ASSERT_EQ(gf < 0, gs < 0);
                if (gf >= 0) {
                    EXPECT_EQ(full.gatherPosition[gf], sub.gatherPosition[gs]);
                    ++compared;
                }
            }
    EXPECT_GT(compared, 5000);
    EXPECT_EQ(sub.slot(r.items.sampleIndex(1, 0, 0)), -1);  // off the sub-grid
    EXPECT_THROW(renderRadiosity(r.items, sub, r.solver->scene()), std::invalid_argument);
}

TEST(LightingBuffer, TheFinestStrideThatFitsTheTimeLeft) {
    // A stride-4 probe took 0.1 s: stride 2 costs 0.4 s, stride 1 1.6 s (rays per pixel).
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, 2.0), 1);
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, 1.6), 1);  // exactly the prediction fits
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, 1.0), 2);
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, 0.3), 4);  // nothing finer fits: the probe
    EXPECT_EQ(finestStrideWithin(0.1, 8, 2, 0.5), 4);  // a large photo's plan of stride 2
    // The limits: no time left, a deadline passed, NaN, a probe of no measurable time.
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, 0.0), 4);
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, -1.0), 4);
    EXPECT_EQ(finestStrideWithin(0.1, 4, 1, std::nan("")), 4);
    EXPECT_EQ(finestStrideWithin(0.0, 4, 1, 1e-9), 1);
    EXPECT_EQ(finestStrideWithin(0.1, 4, 4, 100.0), 4);  // the probe is the finest asked
}

TEST(DisplayMap, SameMapAndImageWithOneAndTwoThreads) {
    const Relighting& r = test::coarseRoom();
    const auto radiance = radianceOf(r, "back_off");
    const auto ratio = vertexRatio(r.prepared, vertexIrradiance(r.prepared, radiance));
    DisplayMap one, two;
    Image a, b;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = buildDisplayMap(r.items, *r.mesh, r.solver->scene());
        renderRatio(one, r.prepared.photo, ratio, radiance, r.prepared.photoRadiance, a);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = buildDisplayMap(r.items, *r.mesh, r.solver->scene());
        renderRatio(two, r.prepared.photo, ratio, radiance, r.prepared.photoRadiance, b);
    }
    EXPECT_EQ(one.start, two.start);
    EXPECT_EQ(one.vertex, two.vertex);
    EXPECT_EQ(one.weight, two.weight);
    EXPECT_EQ(one.emitterStart, two.emitterStart);
    EXPECT_EQ(one.runWeight, two.runWeight);
    EXPECT_EQ(one.rowRuns, two.rowRuns);
    EXPECT_TRUE(sameBits(a, b));
}

TEST(DisplayMap, LeafRunsRenderAsTheGeneralPixels) {
    // The packed form reads r_0 + sum_i w_i (r_i - r_0) where the general arrays read
    // sum_i w_i r_i: equal where the weights sum to 1, and they do to float rounding
    // (4 weights, each rounded to float: 4 x 6e-8). So the two images agree to 1e-6 of the
    // largest ratio times the photo, far below an 8-bit step (4e-3).
    const Relighting& r = test::coarseRoom();
    const DisplayMap& packed = r.prepared.display;
    ASSERT_EQ(packed.rowRuns.size(), static_cast<size_t>(packed.height) + 1);
    DisplayMap plain = packed;
    plain.rowRuns.clear();
    plain.runs.clear();
    plain.runWeight.clear();
    // Many pixels of the room fall inside one display piece with all their samples: the
    // pieces cover 1 to 4 pixels here (RelightOptions::displayPiecePixels), so a pixel's
    // 4 samples all fall in one piece in about a quarter of the pixels or more.
    int64_t inRuns = 0;
    for (const auto& run : packed.runs)
        if (run.vertex[0] >= 0) inRuns += run.length;
    EXPECT_GT(inRuns, int64_t{packed.width} * packed.height / 5);
    for (const char* edit : {"identity", "back_off", "colours"}) {
        const auto radiance = radianceOf(r, edit);
        const auto ratio = vertexRatio(r.prepared, vertexIrradiance(r.prepared, radiance));
        double maxRatio = 0;
        for (const Rgb& q : ratio) maxRatio = std::max(maxRatio, q.maxComponent());
        const Image a =
            renderRatio(packed, r.prepared.photo, ratio, radiance, r.prepared.photoRadiance);
        const Image b =
            renderRatio(plain, r.prepared.photo, ratio, radiance, r.prepared.photoRadiance);
        double worst = 0;
        for (size_t i = 0; i < a.rgb.size(); ++i) {
            const double t = std::max(static_cast<double>(r.prepared.photo.rgb[i]), 1e-3);
            worst = std::max(
                worst, std::abs(static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i])) / t);
        }
        EXPECT_LT(worst, 1e-6 * std::max(1.0, maxRatio)) << edit;
    }
}

TEST(SamplingPlan, ASixteenthOfTheSamplesKeepsTheRoomsAccuracy) {
    // The room with a budget of 19200 samples: 1 sample per pixel (the coarse settings
    // take 4) and the estimates on every other pixel in x and y, a sixteenth of the
    // samples. The light edits must score no worse than with all the samples, to within
    // 0.005 of rel_rmse (half the spec's noise floor of the data, about 0.01). Measured on
    // this date: back_off 0.0268 against 0.0315, left_off_right_double 0.0193 against
    // 0.0189, colours 0.0252 against 0.0250; the coarse settings' refinement and shadow
    // classification move with the samples, so the change is not small in both directions,
    // but it must not be a loss.
    const Relighting& full = test::coarseRoom();
    RelightOptions o = test::coarseOptions();
    o.sampleBudget = 19200;
    const auto sparse = prepareRelighting(loadScene(kRoom), o);
    ASSERT_EQ(sparse->sampling.spp, 1);
    ASSERT_EQ(sparse->sampling.stride, 2);
    int w = 0, h = 0;
    const auto maskP = readMask(kRoom + "/photo.mask.png", w, h);
    for (const char* edit : {"back_off", "left_off_right_double", "colours"}) {
        const Image truth = readImage(kRoom + "/truth/" + std::string(edit) + ".exr");
        const auto maskT = readMask(kRoom + "/truth/" + std::string(edit) + ".mask.png", w, h);
        const Score a = scoreImage(renderEdit(full.prepared, radianceOf(full, edit)), truth,
                                   full.prepared.photo, maskT, maskP);
        const Score b = scoreImage(renderEdit(sparse->prepared, radianceOf(*sparse, edit)), truth,
                                   sparse->prepared.photo, maskT, maskP);
        EXPECT_LT(b.relRmse, a.relRmse + 0.005) << edit;
    }
}
