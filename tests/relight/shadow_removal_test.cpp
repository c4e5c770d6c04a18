// The effect of real-shadow removal's link correction (relight/pipeline/shadow_removal.h, Loscos
// et al. 2000, Eq. (12)-(15)): what the photo shows in a shadow drives C_link.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

#include "relight/pipeline/shadow_removal.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;
using radiosity::Rgb;

namespace {

/// The room prepared without refinement and without removal, so that two preparations
/// from the same inputs have the same leaves and vertices (the pipeline is deterministic)
/// and removal can be run on each with a different photo texture.
std::unique_ptr<Relighting> prepareBare() {
    RelightOptions o = test::coarseOptions();
    o.shadowRefinement = false;
    o.shadowRemoval = false;
    return prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
}

ShadowRemoval removeWith(Relighting& r, const LeafTexture& texture) {
    return removeRealShadows(*r.solver, *r.mesh, texture, r.prepared.photoRadiance,
                             r.prepared.lighting, r.direct, r.responses);
}

}  // namespace

TEST(ShadowRemoval, DeeperPhotoShadowGivesSmallerLinkCorrection) {
    // Eq. (12)-(13): k_inter = (rho_r / rho_i) (H + Ē) / H grows as the photo's shadow
    // (colour c_i, so rho_i = pi c_i / H_i) gets darker; Eq. (15) then gives
    //     C_link = (X - I) / Dv,   X = (D0 + I) / k_inter,
    // which shrinks as k_inter grows: the darker the real shadow, the more of the light
    // the model says arrives must be taken away to show it. Darkening the photo by a
    // factor s = 0.8 on every pixel of an occluded leaf scales rho_i by s, so k_inter by
    // 1/s where a reference is used, X by s, and C_link by (s X - I) / (X - I), which is s
    // where the indirect light I vanishes and less than s where it does not. References
    // can change (more frontier leaves pass Eq. (10)-(11) against a darker leaf) and I
    // changes a little with the reflectances, so the checks are statistical, over the
    // vertices with a link correction: C_link does not grow at 90 % of them or more, and
    // the median ratio is at most s + 0.05.
    auto a = prepareBare();
    auto b = prepareBare();
    ASSERT_EQ(a->mesh->vertices().size(), b->mesh->vertices().size());
    ASSERT_EQ(a->prepared.leaves, b->prepared.leaves);

    const ShadowRemoval ra = removeWith(*a, *a->texture);
    ASSERT_GT(ra.occluded, 0);

    // The photo with every pixel that lies wholly on occluded leaves darkened.
    constexpr float s = 0.8f;
    const radiosity::Hierarchy& h = b->solver->hierarchy();
    const ItemBuffer& items = b->items;
    Image darker = b->prepared.photo;
    int darkened = 0;
    for (int y = 0; y < items.height; ++y)
        for (int x = 0; x < items.width; ++x) {
            bool occluded = true;
            for (int k = 0; k < items.spp && occluded; ++k) {
                const int idx = items.sampleIndex(x, y, k);
                const int p = items.polygon[idx];
                occluded =
                    p >= 0 && b->solver->scene().polygons[p].light < 0 &&
                    ra.leafClass[h.locateLeaf(p, items.point[idx])] == LeafShadowClass::occluded;
            }
            if (!occluded) continue;
            for (int c = 0; c < 3; ++c) darker.at(x, y)[c] *= s;
            ++darkened;
        }
    ASSERT_GT(darkened, 100);
    const LeafTexture texture(h, b->solver->scene(), items, darker,
                              usablePixels(items, b->solver->scene(), darker));
    const ShadowRemoval rb = removeWith(*b, texture);
    EXPECT_EQ(rb.occluded, ra.occluded);  // the classes come from the model, not the photo
    EXPECT_GE(rb.referenced, ra.referenced);

    std::vector<double> ratio;
    for (size_t v = 0; v < ra.linkCorrection.size(); ++v) {
        const Rgb ca = ra.linkCorrection[v], cb = rb.linkCorrection[v];
        if (ca == Rgb::gray(1.0) || !(ca.maxComponent() > 0)) continue;  // no C_link here
        ratio.push_back((cb[0] + cb[1] + cb[2]) / (ca[0] + ca[1] + ca[2]));
    }
    ASSERT_GT(ratio.size(), 50u);
    const auto notGrown =
        std::count_if(ratio.begin(), ratio.end(), [](double q) { return q <= 1 + 1e-9; });
    EXPECT_GE(static_cast<double>(notGrown), 0.9 * static_cast<double>(ratio.size()));
    std::nth_element(ratio.begin(), ratio.begin() + ratio.size() / 2, ratio.end());
    const double median = ratio[ratio.size() / 2];
    EXPECT_LE(median, static_cast<double>(s) + 0.05);
    std::printf("C_link at %zu vertices: %ld not grown, median ratio %.3f\n", ratio.size(),
                static_cast<long>(notGrown), median);
}
