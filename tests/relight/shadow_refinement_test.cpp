// Texture-based refinement of shadow boundaries (relight/pipeline/shadow_refinement.h, Loscos
// et al. 2000, §4.2) on a scene small enough to know where the shadow is: a floor, a blocker
// above it and a small lamp, photographed from above with the shadow the lamp casts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "radiosity/solver.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/leaf_texture.h"
#include "relight/pipeline/shadow_refinement.h"

using namespace relight;
using radiosity::Rgb;
using radiosity::Vec3;

namespace {

// The floor z = 0, x and y in [-1, 1], facing up; the blocker z = 1, x in [-0.4, -0.1],
// y in [-0.2, 0.2], facing up; the lamp z = 2, x in [-1.1, -0.9], y in [-0.1, 0.1], facing
// down. From the lamp's centre the blocker's shadow on the floor is x in [0.2, 0.8], y in
// [-0.4, 0.4] (twice the blocker, about x = -1); the lamp's size widens each edge into a
// penumbra 0.2 m wide: umbra x in [0.3, 0.7], y in [-0.3, 0.3], light reaching all of the
// lamp outside x in [0.1, 0.9], y in [-0.5, 0.5].
constexpr double kBlockerX0 = -0.4, kBlockerX1 = -0.1, kBlockerY = 0.2, kBlockerZ = 1;
constexpr double kLampX0 = -1.1, kLampX1 = -0.9, kLampY = 0.1, kLampZ = 2;
constexpr Rgb kFloor{0.5, 0.4, 0.3}, kBlocker{0.3, 0.5, 0.4};
const Rgb kLampRadiance = Rgb::gray(10);

/// The scene; without `blocker` the blocker is left out (nothing casts a shadow).
radiosity::Scene shadowScene(bool blocker) {
    radiosity::Scene s;
    s.objects = {"floor", "blocker", "lamp"};
    s.polygons.push_back(
        radiosity::makePolygon({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}, 0, kFloor));
    if (blocker)
        s.polygons.push_back(radiosity::makePolygon({{kBlockerX0, -kBlockerY, kBlockerZ},
                                                     {kBlockerX1, -kBlockerY, kBlockerZ},
                                                     {kBlockerX1, kBlockerY, kBlockerZ},
                                                     {kBlockerX0, kBlockerY, kBlockerZ}},
                                                    1, kBlocker));
    radiosity::Polygon lamp = radiosity::makePolygon({{kLampX0, -kLampY, kLampZ},
                                                      {kLampX0, kLampY, kLampZ},
                                                      {kLampX1, kLampY, kLampZ},
                                                      {kLampX1, -kLampY, kLampZ}},
                                                     2, Rgb{});
    lamp.light = 0;
    s.lights.push_back({"lamp", {static_cast<int>(s.polygons.size())}, kLampRadiance});
    s.polygons.push_back(lamp);
    return s;
}

/// Looking straight down from (0, 0, 5): the floor fills 160 x 160 of 200 x 200 pixels.
Camera cameraAbove() {
    Camera c;
    c.width = c.height = 200;
    c.fx = c.fy = 400;
    c.cx = c.cy = 99.5;
    c.cameraFromWorldR = glm::dmat3(1, 0, 0, 0, -1, 0, 0, 0, -1);
    c.cameraFromWorldT = Vec3(0, 0, 5);
    return c;
}

/// The direct irradiance at floor point x from the lamp, blocker included, by a 16 x 16
/// midpoint rule over the lamp's face (radiosity units).
double floorIrradiance(const Vec3& x, bool blocker = true) {
    constexpr int n = 16;
    const double dA = (kLampX1 - kLampX0) * (2 * kLampY) / (n * n);
    double E = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 q(kLampX0 + (kLampX1 - kLampX0) * (i + 0.5) / n,
                         -kLampY + 2 * kLampY * (j + 0.5) / n, kLampZ);
            // Where the segment x -> q crosses the blocker's plane.
            const double t = (kBlockerZ - x.z) / (q.z - x.z);
            const Vec3 b = x + t * (q - x);
            if (blocker && b.x > kBlockerX0 && b.x < kBlockerX1 && std::abs(b.y) < kBlockerY)
                continue;
            const Vec3 d = q - x;
            const double r2 = glm::dot(d, d), cosine = d.z / std::sqrt(r2);  // both faces
            E += cosine * cosine / (std::numbers::pi * r2) * dA;
        }
    return std::numbers::pi * kLampRadiance.r * E;
}

/// A poster on the floor, x in [0.2, 0.8], y in [-0.4, 0.4] (where the blocker's shadow
/// falls): a different colour, no shadow.
bool onPoster(const Vec3& x) {
    return x.x > 0.2 && x.x < 0.8 && std::abs(x.y) < 0.4;
}
constexpr Rgb kPoster{0.1, 0.2, 0.4};

/// The photo: each pixel the mean over its samples of the radiance rho E / pi they see,
/// E from the lamp with the blocker when `shadow` (the blocker itself, lit from above, a
/// plain colour); with `poster`, the poster's reflectance where it lies.
Image photograph(const radiosity::Scene& scene, const ItemBuffer& items, bool shadow, bool poster) {
    Image photo(items.width, items.height);
    for (int y = 0; y < items.height; ++y)
        for (int x = 0; x < items.width; ++x) {
            Rgb sum;
            for (int k = 0; k < items.spp; ++k) {
                const int idx = items.sampleIndex(x, y, k);
                const int p = items.polygon[idx];
                if (p < 0) continue;
                const Vec3& at = items.point[idx];
                if (scene.polygons[p].light >= 0)
                    sum += kLampRadiance;
                else if (scene.polygons[p].object == 1)
                    sum += kBlocker * (0.01 * kLampRadiance.r);
                else
                    sum += (poster && onPoster(at) ? kPoster : kFloor) *
                           (floorIrradiance(at, shadow) / std::numbers::pi);
            }
            for (int c = 0; c < 3; ++c) photo.at(x, y)[c] = static_cast<float>(sum[c] / items.spp);
        }
    return photo;
}

/// The scene solved (light links at the leaves), its item buffer and photo, and the photo
/// per leaf: what refineShadowBoundaries starts from in the pipeline.
struct ShadowScene {
    radiosity::HierarchicalSolver solver;
    ItemBuffer items;
    Image photo;
    std::unique_ptr<LeafTexture> texture;

    ShadowScene(bool blocker, bool poster)
        : solver(shadowScene(blocker), radiosity::SolverOptions{}) {
        solver.solve();
        items = castItemBuffer(cameraAbove(), solver.scene(), solver.visibility(), 4);
        photo = photograph(solver.scene(), items, blocker, poster);
        texture = std::make_unique<LeafTexture>(solver.hierarchy(), solver.scene(), items, photo,
                                                usablePixels(items, solver.scene(), photo));
    }
};

enum class Region { lit, umbra, across };

/// Where floor leaf n lies: in full light (it sees all of the lamp: outside x in [0.1, 0.9],
/// y in [-0.5, 0.5]), in the umbra, or across the penumbra.
Region regionOf(const radiosity::Node& n) {
    double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
    for (int i = 0; i < n.vertexCount; ++i) {
        x0 = std::min(x0, n.v[i].x);
        x1 = std::max(x1, n.v[i].x);
        y0 = std::min(y0, n.v[i].y);
        y1 = std::max(y1, n.v[i].y);
    }
    if (x1 <= 0.1 || x0 >= 0.9 || y1 <= -0.5 || y0 >= 0.5) return Region::lit;
    if (x0 >= 0.3 && x1 <= 0.7 && y0 >= -0.3 && y1 <= 0.3) return Region::umbra;
    return Region::across;
}

/// The floor's leaf elements.
std::vector<int> floorLeaves(const radiosity::Hierarchy& h) {
    std::vector<int> out;
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n)
        if (!h.nodes[n].isCluster() && h.nodes[n].isLeaf() && h.nodes[n].polygon == 0)
            out.push_back(n);
    return out;
}

}  // namespace

TEST(ShadowRefinement, RefinesAcrossTheShadowBoundaryOnly) {
    // Case 1 and 2 of §4.2 fire where the photo's shadow and the model's visibility of the
    // lamp disagree at the leaves' size: across the penumbra. Leaves in full light and in
    // the umbra agree with their neighbours in both and stay whole.
    ShadowScene s(/*blocker=*/true, /*poster=*/false);
    const radiosity::Hierarchy& h = s.solver.hierarchy();
    const std::vector<int> before = floorLeaves(h);
    const ShadowRefinementReport rep = refineShadowBoundaries(s.solver, *s.texture);
    int leaves[3] = {}, split[3] = {};
    for (int n : before) {
        const int r = static_cast<int>(regionOf(h.nodes[n]));
        ++leaves[r];
        split[r] += h.nodes[n].isLeaf() ? 0 : 1;
    }
    std::printf(
        "%d + %d splits kept, %d undone; leaves %d -> %d; split: %d of %d lit, %d of %d "
        "in the umbra, %d of %d across\n",
        rep.splitSameColour, rep.splitDifferentColour, rep.undone, rep.leavesBefore,
        rep.leavesAfter, split[0], leaves[0], split[1], leaves[1], split[2], leaves[2]);
    ASSERT_GT(leaves[0], 20);
    ASSERT_GT(leaves[2], 8);
    EXPECT_EQ(split[static_cast<int>(Region::lit)], 0);
    EXPECT_EQ(split[static_cast<int>(Region::umbra)], 0);
    EXPECT_GE(4 * split[static_cast<int>(Region::across)],
              leaves[static_cast<int>(Region::across)]);
    EXPECT_GT(rep.leavesAfter, rep.leavesBefore);
}

TEST(ShadowRefinement, ModelFollowsThePhotosShadowBetterAfterRefinement) {
    // The model's visibility of the lamp at a point is its leaf's, V = F V / F of the leaf's
    // link; the truth is the fraction of the lamp's light the blocker lets through. Over the
    // floor samples of the penumbra band, the mean error falls by more than a fifth.
    ShadowScene s(/*blocker=*/true, /*poster=*/false);
    const radiosity::Hierarchy& h = s.solver.hierarchy();
    auto visibilityError = [&]() {
        double sum = 0;
        int n = 0;
        for (size_t i = 0; i < s.items.polygon.size(); ++i) {
            const Vec3& x = s.items.point[i];
            if (s.items.polygon[i] != 0 || x.x < 0.1 || x.x > 0.9 || std::abs(x.y) > 0.5) continue;
            const auto ex = s.solver.lightExchange(h.locateLeaf(0, x));
            const double model = ex[0].F > 0 ? ex[0].FV / ex[0].F : 0;
            sum += std::abs(model - floorIrradiance(x, true) / floorIrradiance(x, false));
            ++n;
        }
        return sum / n;
    };
    const double before = visibilityError();
    refineShadowBoundaries(s.solver, *s.texture);
    const double after = visibilityError();
    std::printf("mean |V_model - V_true| in the penumbra band: %.4f -> %.4f\n", before, after);
    EXPECT_LT(after, 0.8 * before);
}

TEST(ShadowRefinement, APosterIsNotAShadow) {
    // Case 2 on a poster (Fig. 11(a)): leaves of another colour than their neighbours but
    // the same visibility are split, their children see the lamp alike, and every split is
    // undone.
    ShadowScene s(/*blocker=*/false, /*poster=*/true);
    const int leaves = static_cast<int>(floorLeaves(s.solver.hierarchy()).size());
    const ShadowRefinementReport rep = refineShadowBoundaries(s.solver, *s.texture);
    EXPECT_GT(rep.undone, 0);
    EXPECT_EQ(rep.splitSameColour + rep.splitDifferentColour, 0);
    EXPECT_EQ(static_cast<int>(floorLeaves(s.solver.hierarchy()).size()), leaves);
}
