// Real-object removal (Loscos et al. 1999, §4.4, §5.3; relight/dynamic/object_removal.h): the
// room's table taken out against the path tracer's room without it, the mask and the fill,
// and the photo given back when the table comes back.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/edit_file.h"
#include "relight/relighting.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;

namespace {

const std::string kRoom = RELIGHT_DATA_DIR "/room";

RelightOptions options() {
    RelightOptions o = test::coarseOptions();
    o.pixelLight = true;
    return o;
}

/// The lights' radiances as the photo shows them: the state every removal starts from.
std::vector<radiosity::Rgb> photoRadiance(const Relighting& r) {
    return {r.prepared.photoRadiance.begin(), r.prepared.photoRadiance.end()};
}

}  // namespace

TEST(ObjectRemoval, TheRoomWithoutItsTableMeetsTheTruth) {
    // The bounds: 0.08 over the image, 0.25 over the blocks the removal changes;
    // the unedited photo scores 0.15 and 0.50 there. The full-setting figures (bench/
    // RESULTS.md) are 0.023 / 0.065: these coarse settings (4 samples per pixel, a coarser
    // solution) leave room for their noise within the bounds, but not for a fill that
    // leaves the table's colour or its shadows in place.
    const auto out = test::renderEditIn(kRoom, "remove_table", options(),
                                        {DisplayMode::pixel, DisplayMode::ratio});
    const Relighting& r = *out.relighting;
    const Score photo =
        test::scoreAgainstTruth(kRoom, "remove_table", r.prepared.photo, r.prepared.photo);
    for (size_t m = 0; m < out.images.size(); ++m) {
        SCOPED_TRACE(m == 0 ? "pixel display" : "ratio display");
        const Score s =
            test::scoreAgainstTruth(kRoom, "remove_table", out.images[m], r.prepared.photo);
        EXPECT_LE(s.relRmse, 0.08);
        EXPECT_LE(s.changedRelRmse, 0.25);
        EXPECT_LT(s.changedRelRmse, 0.5 * photo.changedRelRmse);
    }
}

TEST(ObjectRemoval, TheMaskCoversTheObjectAndTheTableComesBackExactly) {
    auto r = prepareRelighting(loadScene(kRoom), options());
    DynamicRelighting dyn(*r, photoRadiance(*r));
    const Image before = dyn.render(DisplayMode::pixel);
    dyn.removeObject("table");
    const RemovedRegion& g = dyn.removedRegion();
    ASSERT_FALSE(g.empty());
    // Every pixel with a sample on the table is in the mask, and each mask pixel that sees
    // a surface now got a reflectance, from the photo (the room shows its floor and walls).
    const auto& scene = r->solver->scene();
    const int table = scene.findObject("table");
    int covered = 0, masked = 0;
    std::vector<char> onTablePixel(r->items.polygon.size() / static_cast<size_t>(r->items.spp), 0);
    for (int y = 0; y < r->items.height; ++y)
        for (int x = 0; x < r->items.width; ++x) {
            bool onTable = false;
            for (int s = 0; s < r->items.spp; ++s) {
                const int p = r->items.polygon[static_cast<size_t>(r->items.sampleIndex(x, y, s))];
                onTable =
                    onTable || (p >= 0 && scene.polygons[static_cast<size_t>(p)].object == table);
            }
            covered += onTable ? 1 : 0;
            onTablePixel[static_cast<size_t>(y * r->items.width + x)] = onTable ? 1 : 0;
            masked += g.inMask(x, y) ? 1 : 0;
            if (onTable) {
                EXPECT_TRUE(g.inMask(x, y)) << x << " " << y;
            }
        }
    EXPECT_GT(covered, 500);
    EXPECT_GE(masked, covered);
    // The ring around the table keeps the photo's reflectance (object_removal.h).
    EXPECT_EQ(g.filled + g.modelled + g.ring, masked);
    EXPECT_GT(g.ring, 0);
    EXPECT_EQ(g.modelled, 0);
    const Image without = dyn.render(DisplayMode::pixel);
    // The fill shows no table: the pixels it covered are the floor's and the wall's browns
    // and greys, not the table's green (green above red by a third). (The ring around it keeps
    // the photo's reflectance: the poster's blue there is the poster's.)
    int green = 0;
    for (int y = g.y0; y < g.y0 + g.height; ++y)
        for (int x = g.x0; x < g.x0 + g.width; ++x) {
            if (!onTablePixel[static_cast<size_t>(y * r->items.width + x)]) continue;
            const float* p = without.at(x, y);
            green += p[1] > 1.33f * p[0] ? 1 : 0;
        }
    EXPECT_EQ(green, 0);
    // Back: the photo's display as it was (the per-pixel direct light is measured again with
    // the same rays, the solver restored bit for bit).
    dyn.removeLast();
    EXPECT_TRUE(dyn.removedRegion().empty());
    const Image back = dyn.render(DisplayMode::pixel);
    double worst = 0;
    for (size_t i = 0; i < back.rgb.size(); ++i)
        worst = std::max(worst, std::abs(static_cast<double>(back.rgb[i] - before.rgb[i])) /
                                    (1e-3 + std::abs(static_cast<double>(before.rgb[i]))));
    EXPECT_LT(worst, 1e-5);
}

TEST(ObjectRemoval, WhatCannotBeTakenOutIsRefused) {
    auto r = prepareRelighting(loadScene(kRoom), options());
    DynamicRelighting dyn(*r, photoRadiance(*r));
    EXPECT_THROW(dyn.removeObject("sofa"), std::invalid_argument);
    dyn.removeObject("cabinet");
    EXPECT_THROW(dyn.removeObject("cabinet"), std::invalid_argument);
    dyn.removeObject("table");
    dyn.removeLast();
    dyn.removeLast();
    EXPECT_TRUE(dyn.removedRegion().empty());
}

TEST(ObjectRemoval, TakenOutAmongVirtualPartsAndUndoneInTurn) {
    // A virtual lamp and box, then the table out, then each undone, last first: the image
    // before each step comes back (the solver's snapshots, the per-pixel light measured
    // again with the same rays).
    auto r = prepareRelighting(loadScene(kRoom), options());
    const EditFile e = loadEdit(kRoom + "/edits/virtual_light_and_box.json", r->scene);
    DynamicRelighting dyn(*r, editRadiance(r->scene, e, r->prepared.photoRadiance));
    const auto same = [](const Image& a, const Image& b) {
        double worst = 0;
        for (size_t i = 0; i < a.rgb.size(); ++i)
            worst = std::max(worst, std::abs(static_cast<double>(a.rgb[i] - b.rgb[i])) /
                                        (1e-3 + std::abs(static_cast<double>(b.rgb[i]))));
        return worst;
    };
    dyn.addLight(e.addLights.at(0));
    const Image lamp = dyn.render(DisplayMode::pixel);
    dyn.addObject(e.addObjects.at(0));
    const Image box = dyn.render(DisplayMode::pixel);
    dyn.removeObject("table");
    const RemovedRegion& g = dyn.removedRegion();
    ASSERT_FALSE(g.empty());
    const Image without = dyn.render(DisplayMode::pixel);
    EXPECT_GT(same(without, box), 0.1);
    dyn.removeLast();  // the table back
    EXPECT_LT(same(dyn.render(DisplayMode::pixel), box), 1e-5);
    dyn.removeLast();  // the box out
    EXPECT_LT(same(dyn.render(DisplayMode::pixel), lamp), 1e-5);
}

namespace {

/// The chromaticity (r, g) / (r + g + b) of a pixel; (0, 0) for black.
std::array<double, 2> chroma(const float* p) {
    const double r = static_cast<double>(p[0]), g = static_cast<double>(p[1]);
    const double s = r + g + static_cast<double>(p[2]);
    if (!(s > 1e-6)) return {0, 0};
    return {r / s, g / s};
}

/// The colours of a set of the photo's pixels: a histogram of their chromaticity in bins of
/// 0.01 (the photo's noise at 16 samples per pixel moves a pixel's by less than that). A
/// colour is one of them when its bin or a neighbour holds at least 0.2 % of the pixels
/// (a few stray pixels on an edge do not make a colour theirs).
struct Colours {
    static constexpr int kBins = 100;
    std::vector<int> count = std::vector<int>(kBins * kBins, 0);
    int pixels = 0;
    static int bin(double c) { return std::clamp(static_cast<int>(c * kBins), 0, kBins - 1); }
    void add(const float* p) {
        const auto c = chroma(p);
        ++count[static_cast<size_t>(bin(c[0]) * kBins + bin(c[1]))];
        ++pixels;
    }
    bool holds(const float* p) const {
        const auto c = chroma(p);
        const int i = bin(c[0]), j = bin(c[1]);
        int n = 0;
        for (int a = std::max(0, i - 1); a <= std::min(kBins - 1, i + 1); ++a)
            for (int b = std::max(0, j - 1); b <= std::min(kBins - 1, j + 1); ++b)
                n = std::max(n, count[static_cast<size_t>(a * kBins + b)]);
        return n > 0 && n >= 0.002 * pixels;
    }
};

/// The photo's pixels whose every item-buffer sample is on a polygon with `keep`.
template <class Keep>
Colours photoColours(const Relighting& r, Keep keep) {
    Colours out;
    for (int y = 0; y < r.items.height; ++y)
        for (int x = 0; x < r.items.width; ++x) {
            bool all = true;
            for (int s = 0; s < r.items.spp && all; ++s) {
                const int p = r.items.polygon[static_cast<size_t>(r.items.sampleIndex(x, y, s))];
                all = p >= 0 && keep(p);
            }
            if (all) out.add(r.prepared.photo.at(x, y));
        }
    return out;
}

/// Pixels the removed object covered in the photo (a sample on it) that keep its colour in
/// `image`: one of the object's in the photo and none of the surface the pixel now shows (its
/// colours in the photo where it is seen). The ring around the object (object_removal.h)
/// shows the photo's own pixels, relit: not counted.
int keptColour(const Relighting& r, const RemovedRegion& g, const Image& image,
               const std::string& object) {
    const auto& scene = r.solver->scene();
    const int id = scene.findObject(object);
    const Colours objectColours =
        photoColours(r, [&](int p) { return scene.polygons[static_cast<size_t>(p)].object == id; });
    std::map<int, Colours> surfaces;
    int kept = 0;
    const size_t kk = static_cast<size_t>(g.k * g.k);
    for (int y = g.y0; y < g.y0 + g.height; ++y)
        for (int x = g.x0; x < g.x0 + g.width; ++x) {
            if (!g.inMask(x, y)) continue;
            bool covered = false;
            for (int s = 0; s < r.items.spp && !covered; ++s) {
                const int p = r.items.polygon[static_cast<size_t>(r.items.sampleIndex(x, y, s))];
                covered = p >= 0 && scene.polygons[static_cast<size_t>(p)].object == id;
            }
            if (!covered) continue;
            const size_t b = static_cast<size_t>((y - g.y0) * g.width + x - g.x0);
            // The surface its samples show now; a pixel across two (a corner, the floor's
            // line) blends their colours, in the truth too: left out.
            int sf = -1;
            bool one = true;
            for (size_t s = 0; s < kk && one; ++s) {
                const int p = g.polygon[b * kk + s];
                const int q = p >= 0 && static_cast<size_t>(p) < r.surface.size()
                                  ? r.surface[static_cast<size_t>(p)]
                                  : -1;
                one = q >= 0 && (s == 0 || q == sf);
                sf = q;
            }
            if (!one) continue;
            auto it = surfaces.find(sf);
            if (it == surfaces.end())
                it = surfaces
                         .emplace(sf, photoColours(
                                          r,
                                          [&](int q) {
                                              return static_cast<size_t>(q) < r.surface.size() &&
                                                     r.surface[static_cast<size_t>(q)] == sf;
                                          }))
                         .first;
            if (objectColours.holds(image.at(x, y)) && !it->second.holds(image.at(x, y))) ++kept;
        }
    return kept;
}

/// The mean of (image - truth) over the pixels at Chebyshev distance dMin..dMax from those
/// the removed object covered in the photo (RemovedRegion::covered), relative to the truth's
/// mean there (channels averaged): a light outline around the region shows as a positive bias.
double bandBias(const RemovedRegion& g, const Image& image, const Image& truth, int dMin,
                int dMax) {
    double diff = 0, sum = 0;
    for (int y = std::max(0, g.y0 - dMax); y < std::min(image.height, g.y0 + g.height + dMax); ++y)
        for (int x = std::max(0, g.x0 - dMax); x < std::min(image.width, g.x0 + g.width + dMax);
             ++x) {
            int d = dMax + 1;
            for (int v = y - dMax; v <= y + dMax; ++v)
                for (int u = x - dMax; u <= x + dMax; ++u) {
                    const int bx = u - g.x0, by = v - g.y0;
                    if (bx < 0 || by < 0 || bx >= g.width || by >= g.height ||
                        !g.covered[static_cast<size_t>(by * g.width + bx)])
                        continue;
                    d = std::min(d, std::max(std::abs(u - x), std::abs(v - y)));
                }
            if (d < dMin || d > dMax) continue;
            for (int c = 0; c < 3; ++c) {
                diff += static_cast<double>(image.at(x, y)[c] - truth.at(x, y)[c]);
                sum += static_cast<double>(truth.at(x, y)[c]);
            }
        }
    return sum > 0 ? diff / sum : 0.0;
}

/// No light outline around a removed object: the pixels 2 and 3 beside the covered ones (past
/// the mask's one-pixel growth at 320 x 240) are as right as the ring 4 to 8 pixels out, against
/// the truth. The display's light, which they kept before, read +0.22 (room's cabinet),
/// +0.32 / +0.22 (furnished bookshelf / cabinet) there against +0.02..+0.05 beyond (bench/
/// RESULTS.md, 2026-11-27, fifth session; +0.216 against +0.022 at these test settings).
/// Bounds: 0.06 above the ring's bias, 2.5 times the largest gap measured now (0.023, the
/// bookshelf) and under a third of the outline's excess; 0.10 either way in all (now <= 0.062).
void expectNoOutline(const RemovedRegion& g, const Image& image, const Image& truth) {
    const double band = bandBias(g, image, truth, 2, 3), beyond = bandBias(g, image, truth, 4, 8);
    std::printf("outline: bias 2-3 px %+.3f, 4-8 px %+.3f\n", band, beyond);
    EXPECT_LT(band, beyond + 0.06);
    EXPECT_LT(std::abs(band), 0.10);
}

}  // namespace

TEST(ObjectRemoval, TheCabinetAgainstTwoWallsLeavesNoGhost) {
    // The cabinet stands in the back-left corner, against the brick wall and the plaster
    // one (issue 34): its pixels must show the two walls and the floor rebuilt from their
    // own visible parts, lit by the edited solution. Bounds: the 0.08 / 0.25 (full
    // settings: bench/RESULTS.md); the unedited photo scores 0.045 / 0.305 and the fill from
    // the photo around the hole 0.049 / 0.361, above the changed bound.
    RelightOptions o = options();
    o.epsilon = 1e-4;
    o.spp = 16;
    auto r = prepareRelighting(loadScene(kRoom), o);
    DynamicRelighting dyn(*r, photoRadiance(*r));
    const Image before = dyn.render(DisplayMode::pixel);
    dyn.removeObject("cabinet");
    const RemovedRegion& g = dyn.removedRegion();
    ASSERT_FALSE(g.empty());
    EXPECT_EQ(g.modelled, 0);  // every hidden pixel from its own surface's photo texels
    const Image without = dyn.render(DisplayMode::pixel);
    const Score s = test::scoreAgainstTruth(kRoom, "remove_cabinet", without, r->prepared.photo);
    EXPECT_LE(s.relRmse, 0.08);
    EXPECT_LE(s.changedRelRmse, 0.25);
    // No pixel keeps the cabinet's colour: each shows a colour of the wall or floor it now
    // sees, as the photo shows them elsewhere (its pale grey is none of the brick's).
    EXPECT_EQ(keptColour(*r, g, without, "cabinet"), 0);
    // The photo there is the cabinet: the check is not vacuous.
    EXPECT_GT(keptColour(*r, g, before, "cabinet"), 100);
    expectNoOutline(g, without, readImage(kRoom + "/truth/remove_cabinet.exr"));
    dyn.removeLast();
    const Image back = dyn.render(DisplayMode::pixel);
    EXPECT_EQ(back.rgb, before.rgb);  // bit for bit
}

TEST(ObjectRemoval, ACabinetCutByTheImageBorderLeavesNoGhost) {
    // The room's photo cropped so that the cabinet's silhouette runs off its left border
    // (the camera's principal point moved with the crop, the photo's pixels unchanged): the
    // hidden walls' visible parts lie on one side only, and the hole reaches the border.
    constexpr int kCrop = 122;  // the cabinet spans about x = 105..140 of the 320 pixels
    test::TempDir dir("removal_border");
    SceneFile sf = loadScene(kRoom);
    const Image full = readImage(kRoom + "/photo.exr");
    Image cropped(full.width - kCrop, full.height);
    for (int y = 0; y < cropped.height; ++y)
        for (int x = 0; x < cropped.width; ++x)
            std::copy_n(full.at(x + kCrop, y), 3, cropped.at(x, y));
    writeImage(dir.path() / "photo.exr", cropped);
    sf.photos.at(0).file = dir.path() / "photo.exr";
    sf.camera.width = cropped.width;
    sf.camera.cx -= kCrop;
    RelightOptions o = options();
    o.epsilon = 1e-4;
    o.spp = 16;
    auto r = prepareRelighting(std::move(sf), o);
    DynamicRelighting dyn(*r, photoRadiance(*r));
    const Image before = dyn.render(DisplayMode::pixel);
    dyn.removeObject("cabinet");
    const RemovedRegion& g = dyn.removedRegion();
    ASSERT_FALSE(g.empty());
    EXPECT_EQ(g.x0, 0);  // the hole touches the border
    EXPECT_EQ(g.modelled, 0);
    const Image without = dyn.render(DisplayMode::pixel);
    EXPECT_EQ(keptColour(*r, g, without, "cabinet"), 0);
    EXPECT_GT(keptColour(*r, g, before, "cabinet"), 50);
    dyn.removeLast();
    EXPECT_EQ(dyn.render(DisplayMode::pixel).rgb, before.rgb);  // bit for bit
}

TEST(ObjectRemoval, TheFurnishedRoomsBookshelfAndCabinetMeetTheTruth) {
    // data/furnished (bench/scenes/furnished/, issue 34): a bookshelf with boards and books
    // against the brick wall, a cabinet in the corner against the striped wallpaper and the
    // plaster wall, each removed against its own Cycles truth (noise floor 0.010). Bounds:
    // the 0.08 / 0.25. The unedited photo scores 0.232 / 0.653 (bookshelf) and
    // 0.056 / 0.333 (cabinet); before the ring around the objects was lit at its own points
    // the image scored 0.086 and 0.084 with the default settings (bench/RESULTS.md), above
    // the bound: a bright band beside each object.
    const std::string dir = RELIGHT_DATA_DIR "/furnished";
    RelightOptions o = options();
    o.epsilon = 1e-4;  // as the room's cabinet: the coarse solution left the cabinet at 0.098
    o.spp = 16;
    auto r = prepareRelighting(loadScene(dir), o);
    DynamicRelighting dyn(*r, photoRadiance(*r));
    const Image before = dyn.render(DisplayMode::pixel);
    for (const std::string object : {"bookshelf", "cabinet"}) {
        SCOPED_TRACE(object);
        dyn.removeObject(object);
        const RemovedRegion& g = dyn.removedRegion();
        ASSERT_FALSE(g.empty());
        EXPECT_EQ(g.modelled, 0);
        const Image without = dyn.render(DisplayMode::pixel);
        const Score s =
            test::scoreAgainstTruth(dir, "remove_" + object, without, r->prepared.photo);
        EXPECT_LE(s.relRmse, 0.08);
        EXPECT_LE(s.changedRelRmse, 0.25);
        EXPECT_EQ(keptColour(*r, g, without, object), 0);
        EXPECT_GT(keptColour(*r, g, before, object), 100);  // not vacuous
        expectNoOutline(g, without, readImage(dir + "/truth/remove_" + object + ".exr"));
        dyn.removeLast();
        // Back to the photo's display bit for bit: the direct light measured again at the
        // pixels the removal changed is summed as the preparation summed it (float per
        // sample); summed in double it came back up to 1.5e-8 off.
        EXPECT_EQ(dyn.render(DisplayMode::pixel).rgb, before.rgb);
    }
}
