// The time budget's shares of the phases after the reflectance (RelightOptions): once a
// share is spent, its phase takes its fallback, says so in PreparedImage::budgetReached,
// and the preparation stays a correct one.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "relight/display/ratio_display.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;

TEST(PhaseBudget, ASpentBudgetTakesEveryFallbackAndTheUneditedRoomIsStillThePhoto) {
    RelightOptions o = test::coarseOptions();
    o.pixelLight = true;
    o.pixelGatherCut = true;
    o.timeBudget = 1e-9;  // every share is spent before its phase begins
    const auto r = prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    const PreparedImage& P = r->prepared;
    // The shadow-boundary refinement examined no leaf and made no split.
    EXPECT_TRUE(P.budgetReached & PreparedImage::kShadowRefinementBudget);
    EXPECT_EQ(r->refinement.examined, 0);
    EXPECT_GT(r->refinement.waiting, 0);
    // The gather cast no ray at any of its corners or vertices.
    EXPECT_TRUE(P.budgetReached & PreparedImage::kGatherBudget);
    // The leaves' reflectance from their texture skipped: every leaf element keeps its
    // polygon's reflectance (the estimate from the photo), exactly.
    ASSERT_TRUE(o.leafReflectance);
    EXPECT_TRUE(P.budgetReached & PreparedImage::kLeafReflectanceBudget);
    for (const radiosity::Node& n : r->solver->hierarchy().nodes)
        if (!n.isCluster() && n.isLeaf()) {
            const radiosity::Rgb& rho = r->solver->scene().polygons[n.polygon].rho;
            for (int c = 0; c < 3; ++c) EXPECT_EQ(n.rho[c], rho[c]);
        }
    // The per-pixel display's rays per vertex at their floor, 4 x 4 (the pilot covers 1024
    // vertices; the room has more, so the cut applies).
    ASSERT_GT(P.vertexCount(), 1024u);
    EXPECT_TRUE(P.budgetReached & PreparedImage::kPixelGatherBudget);
    EXPECT_EQ(r->gatherSide, 4);
    EXPECT_EQ(P.vertexIndirect.size(), P.vertexCount() * P.photoRadiance.size());
    // Real-shadow removal skipped: D is the photo's lighting, so the unedited display is
    // the photo, to float rounding of the interpolation weights (1e-5 relative), but on
    // the pixels that show an emitter's radiance.
    EXPECT_TRUE(P.budgetReached & PreparedImage::kShadowRemovalBudget);
    const Image out = renderEdit(P, P.photoRadiance);
    double worst = 0;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const int px = y * out.width + x;
                if (P.display.emitterStart[px] != P.display.emitterStart[px + 1]) continue;
                const double t = P.photo.at(x, y)[c], v = out.at(x, y)[c];
                worst = std::max(worst, std::abs(v - t) / std::max(std::abs(t), 1e-3));
            }
    EXPECT_LT(worst, 1e-5);
    // Past its (nanosecond) budget at the end: said too, as the sixth line.
    EXPECT_TRUE(P.budgetReached & PreparedImage::kBudgetOverrun);
    EXPECT_EQ(phaseBudgetLines(P.budgetReached, o.timeBudget).size(), 6u);
}

TEST(PhaseBudget, ThePixelGatherKeepsItsRaysUnlessAskedToCutThem) {
    RelightOptions o = test::coarseOptions();
    o.pixelLight = true;
    o.timeBudget = 1e-9;
    const auto r = prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    EXPECT_FALSE(r->prepared.budgetReached & PreparedImage::kPixelGatherBudget);
    EXPECT_EQ(r->gatherSide, indirectRaySide(o, r->prepared.vertexCount()));
}

TEST(PhaseBudget, TheRoomAtTheDefaultBudgetTakesNoFallback) {
    // The room prepares in seconds, far inside 60 s: no share is spent.
    const PreparedImage& P = test::coarseRoom().prepared;
    EXPECT_EQ(P.budgetReached & ~7, 0);
    EXPECT_TRUE(phaseBudgetLines(P.budgetReached, 60).empty());
}

TEST(PhaseBudget, TheBudgetCountsFromTheCommandsStartNotThePreparations) {
    // A command sets budgetStart before it loads the scene; the loading's time is then
    // spent from the budget. A start more than a whole budget ago leaves every phase its
    // fallback, as a budget spent before the preparation began must, and the preparation
    // says that it ended past the budget.
    RelightOptions o = test::coarseOptions();
    o.pixelLight = true;
    o.timeBudget = 600;  // far beyond what the room takes, counted from now...
    const auto fresh = prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    EXPECT_EQ(fresh->prepared.budgetReached & ~7, 0);
    o.budgetStart = radiosity::Clock::now() - std::chrono::seconds(700);  // ...or spent
    const auto late = prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    const int spent = PreparedImage::kShadowRefinementBudget | PreparedImage::kGatherBudget |
                      PreparedImage::kLeafReflectanceBudget | PreparedImage::kShadowRemovalBudget;
    EXPECT_EQ(late->prepared.budgetReached & spent, spent);
    EXPECT_TRUE(late->prepared.budgetReached & PreparedImage::kBudgetOverrun);
    EXPECT_TRUE(late->solver->stats().timeBudgetReached);
}
