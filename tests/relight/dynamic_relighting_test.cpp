// Virtual lights and objects in the relit photo (relight/dynamic/dynamic_relighting.h): a session
// without virtual parts is the light edit, removal restores the image exactly, a move
// equals a fresh insertion at the new place, and the room's virtual edits match the
// path-traced truth.
#include "relight/dynamic/dynamic_relighting.h"

#include "radiosity/emitter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "relight/display/debug_views.h"
#include "relight/display/metric.h"
#include "relight/pipeline/pixel_light.h"
#include "room_fixture.h"

using namespace relight;

namespace {

const std::string kRoom = RELIGHT_DATA_DIR "/room";

/// The room prepared once with coarse settings, changeable (sessions insert into its solver
/// and take their parts out when they end). epsilon 3e-4 rather than the other tests' 1e-3:
/// a virtual light's indirect light reaches the walls through far-field cluster links,
/// whose single-direction estimate scores 0.056 on virtual_light_only at 1e-3, 0.038 at
/// 3e-4 and 0.032 at the default 1e-4 (bench/RESULTS.md).
Relighting& room() {
    static const auto r = [] {
        RelightOptions o = test::coarseOptions();
        o.epsilon = 3e-4;
        o.pixelLight = true;  // for the per-pixel display's tests
        return prepareRelighting(loadScene(kRoom), o);
    }();
    return *r;
}

EditFile edit(const std::string& name) {
    return loadEdit(kRoom + "/edits/" + name + ".json", room().scene);
}

std::vector<Rgb> radianceOf(const EditFile& e) {
    return editRadiance(room().scene, e, room().prepared.photoRadiance);
}

double maxAbsDiff(const Image& a, const Image& b) {
    double m = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        m = std::max(m, std::abs(static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i])));
    return m;
}

/// How many values of two images of one size differ by more than `limit`.
size_t countBeyond(const Image& a, const Image& b, double limit) {
    size_t n = 0;
    for (size_t i = 0; i < a.rgb.size(); ++i)
        n +=
            std::abs(static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i])) > limit ? 1 : 0;
    return n;
}

Score score(const std::string& name, const Image& img) {
    int w = img.width, h = img.height;
    return scoreImage(img, readImage(kRoom + "/truth/" + name + ".exr"), room().prepared.photo,
                      readMask(kRoom + "/truth/" + name + ".mask.png", w, h),
                      readMask(kRoom + "/photo.mask.png", w, h));
}

Image renderVirtual(const std::string& name, DisplayMode mode = DisplayMode::ratio) {
    const EditFile e = edit(name);
    DynamicRelighting dyn(room(), radianceOf(e));
    for (const auto& l : e.addLights) dyn.addLight(l);
    for (const auto& o : e.addObjects) dyn.addObject(o);
    return dyn.render(mode);
}

}  // namespace

TEST(DynamicRelighting, WithoutVirtualPartsItIsTheLightEdit) {
    const auto radiance = radianceOf(edit("back_off"));
    DynamicRelighting dyn(room(), radiance);
    const Image a = dyn.render();
    const Image b = renderEdit(room().prepared, radiance);
    // The same vertex values and the same display: identical up to float rounding of the
    // (zero) changes added to them.
    EXPECT_LE(maxAbsDiff(a, b), 1e-6);
}

TEST(DynamicRelighting, RemovingWhatWasAddedRestoresTheImage) {
    const auto radiance = radianceOf(EditFile{});
    DynamicRelighting dyn(room(), radiance);
    const Image before = dyn.render();
    const EditFile e = edit("virtual_light_and_box");
    dyn.addLight(e.addLights.at(0));
    dyn.addObject(e.addObjects.at(0));
    const Image with = dyn.render();
    EXPECT_GT(maxAbsDiff(with, before), 0.1);
    dyn.removeLast();
    dyn.removeLast();
    // The solver's solution is restored bit for bit (radiosity/dynamic_objects_test); the
    // vertex changes are recomputed from it: zero again up to rounding.
    EXPECT_LE(maxAbsDiff(dyn.render(), before), 1e-5);
}

TEST(DynamicRelighting, AMovedBoxEqualsOneInsertedThere) {
    const auto radiance = radianceOf(EditFile{});
    const EditFile movedEdit = edit("virtual_box_moved");
    const VirtualObject& there = movedEdit.addObjects.at(0);
    Image moved, fresh;
    {
        DynamicRelighting dyn(room(), radiance);
        dyn.addObject(edit("virtual_box").addObjects.at(0));
        dyn.render();
        dyn.moveLastObject(there.polygons);
        moved = dyn.render();
        EXPECT_GT(dyn.lastUpdate().linksCut, 0);
        EXPECT_FALSE(dyn.lastUpdate().shadowLeaves.empty());
    }
    {
        DynamicRelighting dyn(room(), radiance);
        dyn.addObject(there);
        fresh = dyn.render();
    }
    // A move is a removal and an insertion: the same solution, except that the gather
    // starts from the previous frame (it stops at the solver's 1e-4 relative tolerance).
    EXPECT_LE(relativeRmsDifference(moved, fresh), 1e-3);
}

TEST(DynamicRelighting, TheRoomsVirtualEditsMatchThePathTracedTruth) {
    // The figures (0.05 overall, 0.15 where the edit changes the image), here at the
    // tests' coarse settings; bench/RESULTS.md has them at the default ones.
    for (const std::string name :
         {"virtual_light_only", "virtual_box", "virtual_box_moved", "virtual_light_and_box"}) {
        const Score s = score(name, renderVirtual(name));
        EXPECT_LE(s.relRmse, 0.05) << name;
        if (s.hasChanged) {
            EXPECT_LE(s.changedRelRmse, 0.15) << name;
        }
        std::printf("%s: rel_rmse %.4f, changed_rel_rmse %.4f\n", name.c_str(), s.relRmse,
                    s.changedRelRmse);
    }
}

TEST(DynamicRelighting, TheBoxShowsItsReflectanceAndCastsAShadow) {
    const auto radiance = radianceOf(EditFile{});
    DynamicRelighting dyn(room(), radiance);
    const Image before = dyn.render();
    dyn.addObject(edit("virtual_box").addObjects.at(0));
    const Image after = dyn.render();
    // Pixels now showing the box are red (its reflectance is (0.7, 0.2, 0.2)); pixels that
    // got darker without turning red are its shadow on real surfaces (through B/D).
    int red = 0, shadow = 0;
    for (int y = 0; y < after.height; ++y)
        for (int x = 0; x < after.width; ++x) {
            const float* a = after.at(x, y);
            const float* b = before.at(x, y);
            if (a[0] > 2.5f * a[1] && a[0] > 2.5f * a[2] && a[0] > 0.01f)
                ++red;
            else if (a[1] < 0.8f * b[1] && a[0] < 0.8f * b[0])
                ++shadow;
        }
    EXPECT_GT(red, 200);  // the 0.3 m box covers ~40 x 40 pixels at 320 x 240
    // Its soft shadows on the floor (four ceiling lamps): about 90 pixels lose more than
    // 20 % at the tests' settings.
    EXPECT_GT(shadow, 40);
}

TEST(DynamicRelighting, TheLeavesUnderTheBoxsShadowFollowIt) {
    // Loscos et al. 2000, Fig. 24(a): the scene's leaves that the box's shadow boundaries
    // cross are split, at most as often as the display splits them into pieces, and only
    // among the leaves whose links from the lamps the box's shaft cut.
    const auto radiance = radianceOf(EditFile{});
    const EditFile e = edit("virtual_box");
    const Relighting& r = room();
    const size_t prepared = r.solver->hierarchy().nodes.size();
    const size_t polygons = r.solver->scene().polygons.size();
    Score refined, plain;
    // The edit's mesh view (render --debug-views, mesh_edit.png) marks the split leaves' edges
    // in cyan: none before the box, some after.
    const auto cyan = [&] {
        const Image m = editMeshView(r, prepared);
        int n = 0;
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width; ++x)
                n += m.at(x, y)[0] < 0.01f && m.at(x, y)[1] > 0.8f && m.at(x, y)[2] > 0.99f;
        return n;
    };
    EXPECT_EQ(cyan(), 0);
    {
        DynamicRelighting dyn(room(), radiance);
        dyn.addObject(e.addObjects.at(0));
        EXPECT_GT(cyan(), 100);
        const auto& u = dyn.lastUpdate();
        EXPECT_GT(u.shadowSplits, 0);
        const auto& nodes = r.solver->hierarchy().nodes;
        const std::set<int> cut(u.shadowLeaves.begin(), u.shadowLeaves.end());
        int split = 0;
        for (size_t n = 0; n < prepared; ++n) {
            const auto& leaf = nodes[n];
            if (leaf.isCluster() || leaf.isLeaf() ||
                static_cast<size_t>(leaf.firstChild) < prepared)
                continue;
            ++split;
            EXPECT_TRUE(cut.count(static_cast<int>(n))) << n;
            int depth = 0;
            std::vector<std::pair<int, int>> stack{{static_cast<int>(n), 0}};
            while (!stack.empty()) {
                const auto [m, d] = stack.back();
                stack.pop_back();
                depth = std::max(depth, d);
                for (int k = 0; k < nodes[m].childCount; ++k)
                    stack.push_back({nodes[m].firstChild + k, d + 1});
            }
            EXPECT_LE(depth, r.mesh->splits(static_cast<int>(n))) << n;
        }
        // Every split counted: the scene's leaves', and their children's below them.
        int inner = 0;
        for (size_t n = prepared; n < nodes.size(); ++n)
            inner += !nodes[n].isCluster() && !nodes[n].isLeaf() &&
                     static_cast<size_t>(nodes[n].polygon) < polygons;
        EXPECT_GT(split, 0);
        EXPECT_EQ(split + inner, u.shadowSplits);
        refined = score("virtual_box", dyn.render(DisplayMode::pixel));
    }
    {
        DynamicRelighting dyn(room(), radiance);
        r.solver->setNewShadowSplits({});
        dyn.addObject(e.addObjects.at(0));
        EXPECT_EQ(dyn.lastUpdate().shadowSplits, 0);
        plain = score("virtual_box", dyn.render(DisplayMode::pixel));
    }
    std::printf("virtual_box, changed_rel_rmse: %.4f with the leaves split, %.4f without\n",
                refined.changedRelRmse, plain.changedRelRmse);
    EXPECT_LT(refined.changedRelRmse, plain.changedRelRmse);
}

// The per-pixel display with virtual parts (Loscos et al. 1999, §5.2): the direct light
// measured again at the pixels whose leaves a part's shaft touched, every pixel for a
// virtual light.

TEST(DynamicRelighting, ThePixelDisplayWithoutVirtualPartsIsTheLightEdit) {
    const auto radiance = radianceOf(edit("back_off"));
    DynamicRelighting dyn(room(), radiance);
    // The photo's per-pixel light and zero indirect change: the same sums.
    EXPECT_LE(maxAbsDiff(dyn.render(DisplayMode::pixel),
                         renderEdit(room().prepared, radiance, DisplayMode::pixel)),
              1e-6);
}

TEST(DynamicRelighting, ThePixelDisplayComesBackWhenThePartsAreRemoved) {
    const auto radiance = radianceOf(EditFile{});
    DynamicRelighting dyn(room(), radiance);
    const Image before = dyn.render(DisplayMode::pixel);
    const EditFile e = edit("virtual_light_and_box");
    // The object first: the light's indirect change is then gathered with the object in the
    // solver; when the light goes, the object counts at the leaves again.
    dyn.addObject(e.addObjects.at(0));
    const Image boxOnly = dyn.render(DisplayMode::pixel);  // the box's shadow pixels measured
    dyn.addLight(e.addLights.at(0));
    const Image with = dyn.render(DisplayMode::pixel);
    EXPECT_GT(maxAbsDiff(boxOnly, before), 0.05);
    EXPECT_GT(maxAbsDiff(with, boxOnly), 0.1);
    dyn.removeLast();
    dyn.removeLast();
    // The shadow pixels are measured again with the solver restored bit for bit and the
    // same ray seeds: the photo's light again, up to the indirect change's rounding.
    EXPECT_LE(maxAbsDiff(dyn.render(DisplayMode::pixel), before), 1e-5);
}

TEST(DynamicRelighting, AnInsertedLampsChangeAlongThePreparedRaysIsTheCastGather) {
    // An inserted lamp's indirect change is gathered along the preparation's recorded rays
    // (Relighting::vertexRayHits) instead of casting them again: the leaves they met, looked
    // up again where the lamp's shadows split them, and the lamp's own face met by each ray
    // again. It must give the display that casting every ray gives: the same rays meet the
    // same leaves, so only rounding differs (measured 3e-6; 1e-4 leaves room for a ray that
    // grazes a split line or the face's edge to land on the other side).
    const EditFile e = edit("virtual_light_only");
    auto displayOf = [&] {
        DynamicRelighting dyn(room(), radianceOf(e));
        dyn.addLight(e.addLights.at(0));
        return dyn.render(DisplayMode::pixel);
    };
    ASSERT_FALSE(room().vertexRayHits.empty());
    const Image along = displayOf();
    std::vector<int32_t> hits;
    hits.swap(room().vertexRayHits);
    const Image cast = displayOf();
    hits.swap(room().vertexRayHits);
    EXPECT_LE(maxAbsDiff(along, cast), 1e-4);
    EXPECT_GT(maxAbsDiff(along, renderEdit(room().prepared, radianceOf(e), DisplayMode::pixel)),
              0.01)
        << "the lamp changed nothing: the comparison would hold for any gather";
}

TEST(DynamicRelighting, TheVerticesGatherWaitsForAVertexDisplayAndGivesTheSameValues) {
    // With per-pixel light an inserted lamp's final gather at the vertices (the vertex
    // displays' indirect change) is made only when a vertex display asks for it, or before
    // the solver changes again; the per-pixel render gathers only at the vertices of the
    // pixels it leaves to the ratio display. Each gather is per vertex and deterministic, so
    // every order must give the same values bit for bit (tolerance 0).
    const EditFile e = edit("virtual_light_only");
    const VirtualObject box = edit("virtual_box").addObjects.at(0);
    auto vertexLight = [&](bool pixelFirst, bool objectAfter) {
        DynamicRelighting dyn(room(), radianceOf(e));
        dyn.addLight(e.addLights.at(0));
        Image img;
        if (pixelFirst) img = dyn.render(DisplayMode::pixel);
        if (objectAfter) dyn.addObject(box);  // completes the lamp's gather first
        return std::make_pair(dyn.vertexIrradiance(), img);
    };
    const auto [eager, unused] = vertexLight(false, false);
    const auto [afterPixel, img] = vertexLight(true, false);
    EXPECT_EQ(eager, afterPixel) << "a gather completed in two steps differs";
    // The render made before the gather was complete: the same image as after it.
    {
        DynamicRelighting dyn(room(), radianceOf(e));  // one at a time on the room's solver
        dyn.addLight(e.addLights.at(0));
        (void)dyn.vertexIrradiance();
        EXPECT_EQ(maxAbsDiff(dyn.render(DisplayMode::pixel), img), 0.0);
    }
    // Before the solver changes again the gather is completed with its own links.
    const auto [withObject, unused2] = vertexLight(true, true);
    DynamicRelighting ref(room(), radianceOf(e));
    ref.addLight(e.addLights.at(0));
    (void)ref.vertexIrradiance();
    ref.addObject(box);
    EXPECT_EQ(withObject, ref.vertexIrradiance());
}

TEST(DynamicRelighting, TheRatioMapGathersAsThePixelDisplayAndGivesTheFullGathersImage) {
    // The ratio map (000 Eq. 3) draws per pixel as the pixel display does: its render
    // gathers only at the vertices of the pixels left to the ratio display and leaves the
    // leaf runs out, as DisplayMode::pixel. Its image must be the one of the former path
    // (every vertex's ratio, leaf runs, then the per-pixel pixels and the overlay) bit for
    // bit: the same gather per vertex, and the leaf runs' pixels are all drawn again per
    // pixel (tolerance 0).
    const EditFile e = edit("virtual_light_and_box");
    DynamicRelighting dyn(room(), radianceOf(e));
    dyn.addObject(e.addObjects.at(0));
    dyn.addLight(e.addLights.at(0));
    const Image fast = dyn.render(DisplayMode::ratioMap);
    const PreparedImage& P = room().prepared;
    const std::span<const Rgb> all = dyn.radiance();
    const std::span<const Rgb> real = all.first(static_cast<size_t>(dyn.realLights()));
    Image ref = renderRatio(P.display, P.photo, dyn.vertexRatios(), real, P.photoRadiance);
    const std::vector<Rgb> noIndirect(P.vertexIndirect.size());
    renderPixelLight(P.display, P.photo, P.pixelDirect, noIndirect, all, P.photoRadiance,
                     ratioFloor(P.D), ref, PixelLightChange{dyn.pixelDirect(), {}});
    applyOverlay(ref, dyn.overlay());
    EXPECT_EQ(maxAbsDiff(fast, ref), 0.0);
    EXPECT_GT(maxAbsDiff(fast, P.photo), 0.05) << "the edit changed nothing";
}

TEST(DynamicRelighting, ThePixelDisplayOfTheRoomsVirtualEditsIsAtLeastAsNearTheTruth) {
    // Measured at the default settings (bench/RESULTS.md, 2026-11-25): room-multi's
    // virtual_light_only 0.0210 (ratio) against 0.0108 (pixel); the box edits within 0.001.
    // Here, at the tests' coarse settings: within the bounds, and no worse than
    // the ratio display by more than 0.002 (a tenth of the bound's margin; block noise of
    // the coarse preparation).
    for (const std::string name :
         {"virtual_light_only", "virtual_box", "virtual_box_moved", "virtual_light_and_box"}) {
        const Score pixel = score(name, renderVirtual(name, DisplayMode::pixel));
        const Score ratio = score(name, renderVirtual(name, DisplayMode::ratio));
        std::printf("%s: pixel %.4f / %.4f, ratio %.4f / %.4f\n", name.c_str(), pixel.relRmse,
                    pixel.changedRelRmse, ratio.relRmse, ratio.changedRelRmse);
        EXPECT_LE(pixel.relRmse, 0.05) << name;
        EXPECT_LE(pixel.relRmse, ratio.relRmse + 0.002) << name;
        if (pixel.hasChanged) {
            EXPECT_LE(pixel.changedRelRmse, 0.15) << name;
        }
    }
}

TEST(DynamicRelighting, ThePixelDisplayNeedsAPreparationWithPerPixelLight) {
    Relighting& r = room();
    const std::vector<float> kept = r.prepared.pixelDirect;
    r.prepared.pixelDirect.clear();
    {
        DynamicRelighting dyn(r, radianceOf(EditFile{}));
        EXPECT_THROW(dyn.render(DisplayMode::pixel), std::invalid_argument);
    }
    r.prepared.pixelDirect = kept;
}

TEST(DynamicRelighting, ASessionLeavesTheNextOneThePreparedSolutionBitForBit) {
    // A session puts the solver back as it found it: the next session with the same point
    // lamp gives the same image, tolerance 0 (the viewer opens a session per edit, and the
    // cache's prepared state must not drift with them). Before the fix, the removed lamp's
    // direct light stayed in the leaves (up to 5.6 in the relit image), and a gather at the
    // photo's radiances left the solution within its tolerance of the prepared one (7e-4).
    Relighting& r = room();
    const VirtualLight lamp{
        "P", {}, Rgb{}, radiosity::makePointLamp("P", Vec3{2.0, 1.3, 1.2}, Rgb::gray(2.0))};
    const std::vector<Rgb> photo = r.prepared.photoRadiance;
    const auto render = [&] {
        DynamicRelighting d(r, photo);
        d.addLight(lamp);
        return d.render(DisplayMode::pixel);
    };
    const Image first = render();
    const Image second = render();
    ASSERT_EQ(first.rgb.size(), second.rgb.size());
    size_t differ = 0;
    for (size_t i = 0; i < first.rgb.size(); ++i) differ += first.rgb[i] != second.rgb[i];
    EXPECT_EQ(differ, 0u);
}

// The viewer's sessions share a GeometryCache (viewer/session.h): inserting the same box
// again at other radiances takes the direct light's geometry terms from it. The image must
// be, bit for bit, the one a session without the cache draws (`relight render`'s): a
// shadow ray's stream depends on the point and the lamp's face only (direct_light.cpp).
TEST(DynamicRelighting, TheGeometryCacheGivesTheImageOfASessionWithoutIt) {
    const EditFile e = edit("virtual_box");
    std::vector<Rgb> other = radianceOf(e);
    other.at(0) = other[0] * 0.4;  // light 0 at 0.4 of the edit's: another refinement
    GeometryCache cache;
    Image cached;
    {
        DynamicRelighting first(room(), radianceOf(e), &cache);  // fills the cache
        for (const auto& o : e.addObjects) first.addObject(o);
        first.render(DisplayMode::pixel);
    }
    ASSERT_GT(cache.vertexFrom.size(), 0u);
    {
        DynamicRelighting again(room(), other, &cache);
        for (const auto& o : e.addObjects) again.addObject(o);
        cached = again.render(DisplayMode::pixel);
    }
    EXPECT_GT(cache.pixelHits, 0u);  // it did take them from the cache
    EXPECT_GT(cache.vertexHits, 0u);
    DynamicRelighting fresh(room(), other);
    for (const auto& o : e.addObjects) fresh.addObject(o);
    const Image img = fresh.render(DisplayMode::pixel);
    EXPECT_EQ(maxAbsDiff(cached, img), 0.0);
}

// A light's slider moved with a box in the room: setRealRadiances keeps the box's links
// (refined at the radiances it was inserted at) and recombines the direct light from its
// geometry terms.
TEST(DynamicRelighting, ASlidersQuickImageIsNearTheExactOneAndComesBackToIt) {
    const EditFile e = edit("virtual_box");
    const std::vector<Rgb> start = radianceOf(e);
    std::vector<Rgb> other = start;
    other.at(0) = other[0] * 0.4;
    GeometryCache cache;
    Image atStart, quick, back;
    {
        DynamicRelighting dyn(room(), start, &cache);
        for (const auto& o : e.addObjects) dyn.addObject(o);
        atStart = dyn.render(DisplayMode::pixel);
        ASSERT_TRUE(dyn.setRealRadiances(other));
        quick = dyn.render(DisplayMode::pixel);
        ASSERT_TRUE(dyn.setRealRadiances(start));
        back = dyn.render(DisplayMode::pixel);
    }
    DynamicRelighting exact(room(), other, &cache);
    for (const auto& o : e.addObjects) exact.addObject(o);
    const Image img = exact.render(DisplayMode::pixel);
    // Near the insertion at those radiances: what differs is the links the refinement makes
    // at other radiances (its oracle weighs B; Loscos et al. 2000, §5.4), on the box and in
    // its shadow, and the gathers' tolerance. Bound: issue 32's 1/255 between the viewer and
    // render, at all but 0.1 % of the values (seen: 16 of 230 400, all by the box), and
    // 5/255 anywhere (seen: 0.0134, on the box's face). The change itself is far larger:
    // the quick image did follow the light.
    EXPECT_LE(countBeyond(quick, img, 1.0 / 255), img.rgb.size() / 1000);
    EXPECT_LE(maxAbsDiff(quick, img), 5.0 / 255);
    EXPECT_GT(maxAbsDiff(quick, atStart), 20.0 / 255);
    // Back to the radiances it was inserted at, on its own links: the same image within the
    // gathers' tolerance. A gather stops when the total power changes by less than 1e-4
    // (SolverOptions::tolerance); a value converges more slowly than the total, to within
    // about 1e-3 of itself (seen: 6e-4 at a value of 1.6; ~DynamicRelighting says 7e-4 for
    // a solution gathered again). The "before" by linearity adds nothing beyond that.
    for (size_t i = 0; i < back.rgb.size(); ++i)
        ASSERT_NEAR(static_cast<double>(back.rgb[i]), static_cast<double>(atStart.rgb[i]),
                    1e-3 * std::max(std::abs(static_cast<double>(atStart.rgb[i])), 0.01))
            << "value " << i;
}

// What the quick path does not do (its light is not linear at a frame's cost): a virtual
// lamp's indirect light is a gather at every vertex.
TEST(DynamicRelighting, ASliderWithAVirtualLampIsNotQuick) {
    const EditFile e = edit("virtual_light_and_box");
    GeometryCache cache;
    DynamicRelighting dyn(room(), radianceOf(e), &cache);
    for (const auto& l : e.addLights) dyn.addLight(l);
    for (const auto& o : e.addObjects) dyn.addObject(o);
    std::vector<Rgb> other = radianceOf(e);
    other.at(0) = other[0] * 0.4;
    EXPECT_FALSE(dyn.setRealRadiances(other));
    EXPECT_EQ(dyn.radiance()[0], radianceOf(e)[0]);  // unchanged
}

// A box dragged in the viewer's per-pixel display (previewLastObject, issue 32): the quick
// frame at a place against the box inserted there (render's image), and the relighting as
// the drag found it once the quick session ends.
TEST(DynamicRelighting, ADraggedBoxsQuickImageIsNearTheExactOne) {
    const auto radiance = radianceOf(EditFile{});
    const VirtualObject here = edit("virtual_box").addObjects.at(0);
    const VirtualObject there = edit("virtual_box_moved").addObjects.at(0);
    Image exactFirst;
    {
        DynamicRelighting dyn(room(), radiance);
        dyn.addObject(there);
        exactFirst = dyn.render(DisplayMode::pixel);
    }
    GeometryCache cache;
    Image quick;
    std::vector<float> quickDirect;
    {
        DynamicRelighting dyn(room(), radiance, &cache);
        dyn.addObject(here);
        dyn.render(DisplayMode::pixel);
        // The first call takes the box out of the solver; the next ones move it alone.
        ASSERT_TRUE(dyn.previewLastObject(here.polygons));
        ASSERT_TRUE(dyn.previewLastObject(there.polygons));
        EXPECT_TRUE(dyn.previewingObject());
        quick = dyn.render(DisplayMode::pixel);
        const std::span<const float> d = dyn.pixelDirect();
        quickDirect.assign(d.begin(), d.end());
        EXPECT_THROW(dyn.moveLastObject(there.polygons), std::logic_error);
        EXPECT_FALSE(dyn.setRealRadiances(radiance));
    }
    DynamicRelighting exact(room(), radiance, &cache);
    exact.addObject(there);
    const Image img = exact.render(DisplayMode::pixel);
    // The solver went back to the preparation bit for bit: the same image as before the drag.
    EXPECT_EQ(maxAbsDiff(img, exactFirst), 0.0);
    // The direct light per pixel and light: where no ray can meet the box, the cached value
    // of the scene without it, which the exact one also is (the same seeded rays, none
    // blocked); under its shadow, the share it lets through from one camera sample of 16.
    // Bounds: 99 % of the values identical (seen: 99.85 %), 0.5 % off by more than 2 %
    // (seen: 0.12 %: pixels whose samples straddle the shadow's edge or a surface's), and
    // the image's total within 0.5 % (seen: 0.001 %: the shadow takes as much light away).
    const std::span<const float> d = exact.pixelDirect();
    ASSERT_EQ(d.size(), quickDirect.size());
    size_t same = 0, off = 0;
    double sumQuick = 0, sumExact = 0;
    for (size_t i = 0; i < d.size(); ++i) {
        const double a = static_cast<double>(quickDirect[i]), b = static_cast<double>(d[i]);
        same += a == b ? 1 : 0;
        off += std::abs(a - b) > 0.02 * std::max(b, 0.01) ? 1 : 0;
        sumQuick += a;
        sumExact += b;
    }
    EXPECT_GE(same, d.size() * 99 / 100);
    EXPECT_LE(off, d.size() / 200);
    EXPECT_NEAR(sumQuick, sumExact, 0.005 * sumExact);
    // The image: beyond the direct light, the indirect light is the scene's without the box
    // (its bounce and the light it blocks are missing, over the room: up to 0.004 on the
    // walls) and the box's faces keep what they gathered where it was. Bounds: 1 % of the
    // values beyond 1/255 (seen: 0.52 %), none beyond 10/255 (seen: 0.0254, by the box).
    const size_t beyond = countBeyond(quick, img, 1.0 / 255);
    EXPECT_LE(beyond, img.rgb.size() / 100);
    EXPECT_LE(maxAbsDiff(quick, img), 10.0 / 255);
    // Against the path-traced truth, the bounds for the room's virtual edits (0.05,
    // 0.15 where the edit changes the image), as the exact image meets them (seen: quick
    // 0.0126 and 0.103, exact 0.0114 and 0.036: the quick frame's error is the box's own
    // light and the indirect light near it).
    const Score q = score("virtual_box_moved", quick);
    EXPECT_LE(q.relRmse, 0.05);
    EXPECT_LE(q.changedRelRmse, 0.15);
    std::printf(
        "direct: %zu of %zu values equal, %zu off by > 2 %%; image: %zu values beyond "
        "1/255, at most %.4f; truth: rel_rmse %.4f, changed %.4f\n",
        same, d.size(), off, beyond, maxAbsDiff(quick, img), q.relRmse, q.changedRelRmse);
}

// A virtual quad lamp dragged in the viewer (DynamicRelighting::previewEmitter with a quad
// lamp, issue 32 "a virtual lamp ... is dragged"): its quick direct light per pixel at the
// new place (one camera sample, one shadow ray a pixel) against the lamp inserted there
// (the preparation's camera samples, 4 here, each with the lamp's stratified shadow rays).
// The move is a drag's step: 0.15 m along its own plane, so that the lamp's face where the
// solver still holds it overlaps the new one in one plane (it is passed as the lamp's own
// face, as the exact light passes it, and does not block).
TEST(DynamicRelighting, ADraggedQuadLampsQuickDirectLightIsTheExactOneBesideItsPenumbrae) {
    const EditFile e = edit("virtual_light_only");
    const VirtualLight here = e.addLights.at(0);
    VirtualLight there = here;
    for (radiosity::Vec3& c : there.corners) c.x -= 0.15;
    std::vector<float> quick, exact;
    size_t L = 0;
    int light = -1;
    {
        DynamicRelighting dyn(room(), radianceOf(e));
        light = dyn.addLight(here);
        (void)dyn.pixelDirect();
        const std::vector<int> own = room().solver->scene().lights.at(light).polygons;
        ASSERT_EQ(own.size(), 1u);
        // A lamp of faces is shown moved as a quad only.
        EXPECT_THROW(dyn.previewEmitter(light, *radiosity::makePointLamp("V1", {2, 1.6, 2}, {})),
                     std::invalid_argument);
        dyn.previewEmitter(light,
                           *radiosity::makeQuadLamp("V1", {there.corners}, own, Rgb{1, 1, 1}));
        EXPECT_TRUE(dyn.previewing());
        // Its GPU frames' source: the face where it is shown.
        const std::optional<MovedLightFrame> f = dyn.movedLightFrame(light);
        ASSERT_TRUE(f.has_value());
        EXPECT_EQ(f->source.kind, radiosity::ShadowSource::Kind::face);
        EXPECT_EQ(f->source.corners, there.corners);
        L = dyn.radiance().size();
        const std::span<const float> d = dyn.pixelDirect();
        for (size_t px = 0; px < d.size() / L; ++px) quick.push_back(d[px * L + size_t(light)]);
    }
    {
        DynamicRelighting dyn(room(), radianceOf(e));
        ASSERT_EQ(dyn.addLight(there), light);
        const std::span<const float> d = dyn.pixelDirect();
        for (size_t px = 0; px < d.size() / L; ++px) exact.push_back(d[px * L + size_t(light)]);
    }
    ASSERT_EQ(quick.size(), exact.size());
    size_t lit = 0, dark = 0, litOff = 0, darkOff = 0;
    double sumQuick = 0, sumExact = 0, top = 0;
    for (float v : exact) top = std::max(top, static_cast<double>(v));
    for (size_t px = 0; px < exact.size(); ++px) {
        const double q = quick[px], x = exact[px];
        sumQuick += q;
        sumExact += x;
        if (x == 0) {
            ++dark;
            darkOff += q != 0 ? 1 : 0;
        } else if (x > 0.01 * top) {
            ++lit;
            litOff += std::abs(q - x) > 0.1 * x ? 1 : 0;
        }
    }
    std::printf(
        "quad lamp moved 0.15 m: %zu pixels, %zu lit (>1 %% of the top), %zu dark; quick off "
        "by > 10 %% at %zu lit, non-zero at %zu dark; mean %.5f quick, %.5f exact\n",
        exact.size(), lit, dark, litOff, darkOff, sumQuick / static_cast<double>(exact.size()),
        sumExact / static_cast<double>(exact.size()));
    ASSERT_GT(lit, exact.size() / 4) << "the lamp lights a good part of the room";
    // Where no ray of any sample arrives, one ray does not either, but where a sample of the
    // four sees the lamp's edge only by some of its rays (a penumbra's outer rim).
    EXPECT_LE(darkOff, dark / 50 + 1);
    // Lit pixels: the quick value is F at one sample times 0 or 1. Away from penumbrae the
    // form factor changes by a few per cent across a pixel (its footprint of about 1.5 cm at
    // 1-3 m from the lamp); in a penumbra one ray gives 0 or 1. 10 % of the lit pixels off
    // by 10 % would be a penumbra over a tenth of the room: more than the room's objects cast.
    EXPECT_LE(litOff, lit / 10);
    // Over the image, the penumbrae's 0-or-1 average out: within 2 %.
    EXPECT_NEAR(sumQuick, sumExact, 0.02 * sumExact);
}
