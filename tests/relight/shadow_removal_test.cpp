// Real-shadow removal (relight/pipeline/shadow_removal.h, Loscos et al. 2000, §4.3-4.4): the
// effect of the link correction on the room, and each step of the paper on its own.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
    return removeRealShadows(
        *r.solver, r.responses,
        {*r.mesh, texture, r.prepared.photoRadiance, r.prepared.lighting, r.direct});
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

// ---- The steps on their own, on hand-made vertices and leaves ---------------------------

namespace {

/// One vertex of each kind, with the floor of H set to 0 so that the expected values are
/// the paper's formulas exactly. Direct light: D0 unoccluded, Dv visible; I indirect.
VertexShadowLight handMadeLight(const std::vector<Rgb>& D0, const std::vector<Rgb>& Dv,
                                const std::vector<Rgb>& I) {
    VertexShadowLight light;
    light.unoccluded = D0;
    light.visible = Dv;
    for (size_t v = 0; v < D0.size(); ++v) {
        light.H.push_back(Dv[v] + I[v]);
        Rgb blocked;
        for (int c = 0; c < 3; ++c) blocked[c] = std::max(0.0, D0[v][c] - Dv[v][c]);
        light.blocked.push_back(blocked);
    }
    return light;
}

void expectRgbNear(const Rgb& got, const Rgb& want, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], 1e-12 * std::max(1.0, std::abs(want[c])))
            << what << ", channel " << c;
}

}  // namespace

TEST(ShadowRemovalSteps, InterTextureFactorIsEq13WhereLightIsBlocked) {
    // k_inter = q (H + Ē) / H (Eq. (12)-(13)): vertex 0 half in shadow, vertex 1 lit.
    const VertexShadowLight light =
        handMadeLight({{2, 4, 8}, {1, 1, 1}}, {{1, 2, 4}, {1, 1, 1}}, {{1, 0, 0}, {0.5, 0.5, 0.5}});
    // H = (2, 2, 4), Ē = (1, 2, 4) at vertex 0: (H + Ē) / H = (1.5, 2, 2).
    const std::vector<Rgb> q = {{2, 1, 1.25}, {3, 3, 3}};
    const std::vector<Rgb> k = interTextureFactor(q, light);
    ASSERT_EQ(k.size(), 2u);
    expectRgbNear(k[0], {3, 2, 2.5}, "blocked vertex");
    // Nothing blocked: the texture is kept whatever the reference says.
    expectRgbNear(k[1], Rgb::gray(1.0), "lit vertex");
    // The reflectance T_inter shows against the unoccluded irradiance: k_inter H / (H + Ē),
    // the reference's ratio q itself at the blocked vertex.
    const std::vector<Rgb> f = interReflectanceFactor(k, light);
    expectRgbNear(f[0], q[0], "reflectance factor, blocked vertex");
    expectRgbNear(f[1], Rgb::gray(1.0), "reflectance factor, lit vertex");
}

TEST(ShadowRemovalSteps, LinkCorrectionGivesBackThePhotoInPartialShadow) {
    // Eq. (14): the unedited display T_inter B_link / D_inter must give back T_orig, i.e.
    // k_inter (C_link Dv + I) = D0 + I. Vertex 0: partial shadow; 1: umbra (Dv below a tenth
    // of D0); 2: nothing blocked; 3: a texture factor below 1, where Eq. (15) would ask a
    // light for more than it gives unoccluded (clamped to D0 / Dv).
    const std::vector<Rgb> D0 = {{2, 2, 2}, {2, 2, 2}, {1, 1, 1}, {2, 2, 2}};
    const std::vector<Rgb> Dv = {{1, 1.5, 0.8}, {0.1, 0.15, 0.05}, {1, 1, 1}, {1, 1, 1}};
    const std::vector<Rgb> I = {{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.2, 0.2, 0.2}, {0.5, 0.5, 0.5}};
    const VertexShadowLight light = handMadeLight(D0, Dv, I);
    const std::vector<Rgb> kInter = {{1.2, 1.1, 1.3}, {2, 2, 2}, {1, 1, 1}, {0.5, 0.5, 0.5}};
    const LinkCorrection link = linkCorrection(light, light.H, kInter, 0.1);
    EXPECT_EQ(link.partialVertices, 2);
    EXPECT_EQ(link.umbraVertices, 1);
    EXPECT_EQ(link.umbra, (std::vector<bool>{false, true, false, false}));
    Rgb shown;
    for (int c = 0; c < 3; ++c) shown[c] = kInter[0][c] * (link.factor[0][c] * Dv[0][c] + I[0][c]);
    expectRgbNear(shown, D0[0] + I[0], "k_inter (C_link Dv + I)");
    for (int c = 0; c < 3; ++c) {  // within [0, D0 / Dv]: not clamped here
        EXPECT_GT(link.factor[0][c], 0.0);
        EXPECT_LT(link.factor[0][c], D0[0][c] / Dv[0][c]);
    }
    expectRgbNear(link.factor[1], Rgb::gray(1.0), "umbra: no link correction");
    expectRgbNear(link.factor[2], Rgb::gray(1.0), "nothing blocked");
    // ((2 + 0.5) / 0.5 - 0.5) / 1 = 4.5 asks more than D0 / Dv = 2.
    expectRgbNear(link.factor[3], Rgb::gray(2.0), "clamped");
}

TEST(ShadowRemovalSteps, UmbraCorrectionClosesTheDisplayInTheUmbra) {
    // Eq. (16): T_final = C_umbra T_inter with C_umbra = (Hinter + Ē) / (k_inter Hlink), so
    // that k_inter C_umbra Hlink = Hinter + Ē: the unedited display shows T_orig. Only the
    // umbra vertices are changed.
    const VertexShadowLight light = handMadeLight(
        {{2, 2, 2}, {2, 2, 2}}, {{0.1, 0.1, 0.1}, {1, 1, 1}}, {{0.4, 0.3, 0.2}, {0, 0, 0}});
    const std::vector<Rgb> Hinter = {{0.6, 0.5, 0.4}, {1, 1, 1}};
    const std::vector<Rgb> Hlink = {{0.5, 0.45, 0.25}, {1, 1, 1}};
    const std::vector<Rgb> kInter = {{4, 5, 6}, {1.5, 1.5, 1.5}};
    const std::vector<Rgb> u = umbraCorrection(light, Hinter, Hlink, kInter, {true, false});
    Rgb shown;
    for (int c = 0; c < 3; ++c) shown[c] = kInter[0][c] * u[0][c] * Hlink[0][c];
    expectRgbNear(shown, Hinter[0] + light.blocked[0], "k_inter C_umbra Hlink");
    expectRgbNear(u[1], Rgb::gray(1.0), "not in the umbra");
}

TEST(ShadowRemovalSteps, ClosedTextureFactorMakesTheUneditedDisplayThePhoto) {
    // D_final = H_final + Ē and k_final B / D = 1 through the display's own ratio, umbra
    // (H_final = 0) and a vertex in the dark included.
    const std::vector<Rgb> Hfinal = {{1, 2, 3}, {0, 0, 0}, {0.5, 0.25, 0.125}, {0, 0, 0}};
    const std::vector<Rgb> blocked = {{0, 0, 0}, {2, 2, 2}, {0.5, 0.5, 0.5}, {0, 0, 0}};
    const FinalDisplay closed = closeDisplay(Hfinal, blocked);
    const std::vector<Rgb> ratio = displayRatio(Hfinal, closed.D);
    for (size_t v = 0; v < Hfinal.size(); ++v) {
        expectRgbNear(closed.D[v], Hfinal[v] + blocked[v], "D_final");
        Rgb shown;
        for (int c = 0; c < 3; ++c) shown[c] = closed.kFinal[v][c] * ratio[v][c];
        expectRgbNear(shown, Rgb::gray(1.0), "k_final B / D");
    }
    EXPECT_GT(closed.kFinal[1].minComponent(), 1e3);  // the umbra's texture is brightened
}

TEST(ShadowRemovalSteps, ReferenceCandidatesFollowEq10And11) {
    const Rgb ci{0.2, 0.1, 0.05}, rho{0.3, 0.3, 0.3};
    EXPECT_TRUE(canBeReference(ci, {0.4, 0.2, 0.1}, rho, rho, 0.1));      // alpha = beta = gamma
    EXPECT_FALSE(canBeReference(ci, {0.1, 0.05, 0.025}, rho, rho, 0.1));  // darker
    EXPECT_FALSE(canBeReference(ci, ci, rho, rho, 0.1));                  // ratios 1: not brighter
    EXPECT_FALSE(canBeReference(ci, {0.4, 0.4, 0.1}, rho, rho, 0.1));     // |alpha - beta| 0.25
    EXPECT_TRUE(canBeReference(ci, {0.4, 0.4, 0.1}, rho, rho, 0.3));      // ... within 0.3
    // Ratios alike (0.48, 0.52, 0.5) but another brightest channel.
    EXPECT_FALSE(canBeReference({0.30, 0.31, 0.1}, {0.62, 0.6, 0.2}, rho, rho, 0.1));
    EXPECT_FALSE(canBeReference(ci, {0.4, 0.2, 0.1}, rho, rho * 0.9, 0.1));  // Eq. (11)
    EXPECT_FALSE(canBeReference(ci, {0.4, 0.2, 0.0}, rho, rho, 0.1));        // a black channel
}

TEST(ShadowRemovalSteps, OccludedLeafTakesTheNearestSimilarFrontierLeaf) {
    // Leaves 0-4 on a line (x = 0, 1, 2, 3, 4): 0 occluded, 1 and 3 frontier, 2 a frontier
    // leaf of another hue, 4 occluded with no brighter frontier leaf. Node 5 is no leaf.
    std::vector<radiosity::Node> nodes(6);
    for (int n = 0; n < 6; ++n) nodes[n].centre = radiosity::Vec3(n, 0, 0);
    using C = LeafShadowClass;
    ShadowClasses classes;
    classes.leafClass = {C::occluded, C::frontier, C::frontier, C::frontier, C::occluded, C::none};
    classes.frontier = {3, 2, 1};  // the nearest wins, whatever the order
    LeafPhotoReflectance leaves;
    leaves.colour = {{0.1, 0.05, 0.05}, {0.2, 0.1, 0.1}, {0.1, 0.2, 0.1},
                     {0.3, 0.15, 0.15}, {0.5, 0.5, 0.5}, {}};
    leaves.rho = {{0.2, 0.1, 0.1}, {0.4, 0.3, 0.1}, {0.5, 0.5, 0.5},
                  {0.6, 0.3, 0.3}, {0.5, 0.5, 0.5}, {}};
    leaves.known = {true, true, true, true, true, false};
    const ShadowReferences refs = chooseReferences(nodes, classes, leaves, 0.1);
    EXPECT_EQ(refs.occluded, 2);
    EXPECT_EQ(refs.referenced, 1);
    EXPECT_EQ(refs.reference, (std::vector<int>{1, -1, -1, -1, 4, -1}));
    // rho_r / rho_i = (2, 3, 1), never below 1 per channel; 1 where there is no reference.
    expectRgbNear(refs.rhoRatio[0], {2, 3, 1}, "leaf 0");
    expectRgbNear(refs.rhoRatio[4], Rgb::gray(1.0), "leaf 4");
}
