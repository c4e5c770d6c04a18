// The ratio display (relight/display/ratio_display.h) and the prepared relighting of the room
// (relight/relighting.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "relight/display/ratio_display.h"
#include "relight/io/edit_file.h"
#include "relight/pipeline/shadow_removal.h"
#include "relight/relighting.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;
using radiosity::Rgb;

TEST(DisplayRatio, GuardsWhereDVanishes) {
    // D is 1 on average per channel, so delta = kRatioFloor.
    const std::vector<Rgb> D = {Rgb::gray(2.0), Rgb::gray(0.0), Rgb::gray(1.0), Rgb::gray(1.0)};
    const std::vector<Rgb> B = {Rgb::gray(2.0), Rgb::gray(0.0), Rgb::gray(3.0), Rgb::gray(0.0)};
    std::vector<Rgb> Bunlit = B;
    Bunlit[1] = Rgb::gray(0.5);  // light reaches a vertex that had none
    const auto r = displayRatio(B, D);
    EXPECT_EQ(r[0], Rgb::gray(1.0));  // B = D: exactly 1, the photo is kept
    EXPECT_EQ(r[1], Rgb::gray(1.0));  // both vanish: 1, not 0/0
    // Far from the guard, B/D to within delta/D = 1e-4 relative.
    EXPECT_NEAR(r[2].r, 3.0, 3.0 * kRatioFloor);
    EXPECT_NEAR(r[3].r, 0.0, kRatioFloor);
    const auto r2 = displayRatio(Bunlit, D);
    // Only D vanishes: finite and bounded by (B + delta) / delta.
    EXPECT_TRUE(std::isfinite(r2[1].r));
    EXPECT_LE(r2[1].r, (0.5 + kRatioFloor) / kRatioFloor * (1 + 1e-12));
    // No light at all in the photo: still finite.
    const std::vector<Rgb> zero(3);
    for (const Rgb& v : displayRatio(zero, zero)) EXPECT_EQ(v, Rgb::gray(1.0));
}

TEST(RenderRatio, EmittersShowTheirCurrentRadianceAndSurfacesTheModulatedPhoto) {
    // Three pixels: all surface (one vertex, weight 1); all emitting face of light 0;
    // half face, half surface.
    DisplayMap m;
    m.width = 3;
    m.height = 1;
    m.start = {0, 1, 1, 2};
    m.vertex = {0, 0};
    m.weight = {1.0f, 0.5f};
    m.unshaded = {0, 0, 0};
    m.emitterStart = {0, 0, 1, 2};
    m.emitterLight = {0, 0};
    m.emitterFraction = {1.0f, 0.5f};
    Image photo(3, 1);
    const float px[3][3] = {{0.2f, 0.3f, 0.4f}, {5, 5, 5}, {2.6f, 2.7f, 2.8f}};
    for (int x = 0; x < 3; ++x)
        for (int c = 0; c < 3; ++c) photo.at(x, 0)[c] = px[x][c];
    const std::vector<Rgb> ratio = {Rgb{2.0, 0.5, 1.0}};
    const std::vector<Rgb> now = {Rgb{1, 2, 3}}, inPhoto = {Rgb::gray(5)};
    const Image out = renderRatio(m, photo, ratio, now, inPhoto);
    // Surface: T * r.
    EXPECT_FLOAT_EQ(out.at(0, 0)[0], 0.4f);
    EXPECT_FLOAT_EQ(out.at(0, 0)[1], 0.15f);
    // Emitting face: the current radiance, whatever the photo showed.
    EXPECT_FLOAT_EQ(out.at(1, 0)[2], 3.0f);
    // Mixed: the surface half is T - 0.5 * 5 = (0.1, 0.2, 0.3) over half the pixel,
    // modulated by r; the face half shows 0.5 * now.
    EXPECT_NEAR(out.at(2, 0)[0], 0.1 * 2.0 + 0.5, 1e-6);
    EXPECT_NEAR(out.at(2, 0)[1], 0.2 * 0.5 + 1.0, 1e-6);
    EXPECT_NEAR(out.at(2, 0)[2], 0.3 * 1.0 + 1.5, 1e-6);
}

TEST(RenderRatio, PixelsWhereThePhotoShowsNoLampAreKeptAsInThePhoto) {
    // The model puts light 0's face (radiance 5 in the photo) on four pixels; the photo
    // shows it on the first (5), half of it on the second (2.6 = 0.5 * 5 + a surface), and
    // none of it on the last two (0.3 and 2.4, both below half of 5: a misplaced lamp).
    DisplayMap m;
    m.width = 4;
    m.height = 1;
    m.start = {0, 0, 0, 0, 0};
    m.unshaded = {0, 0, 0, 0};
    m.emitterStart = {0, 1, 2, 3, 4};
    m.emitterLight = {0, 0, 0, 0};
    m.emitterFraction = {1.0f, 1.0f, 1.0f, 1.0f};
    Image photo(4, 1);
    const float shown[4] = {5.0f, 2.6f, 0.3f, 2.4f};
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) photo.at(x, 0)[c] = shown[x];
    const std::vector<Rgb> inPhoto = {Rgb::gray(5)}, now = {Rgb::gray(1)};
    EXPECT_EQ(trustPhotoAtEmitters(m, photo, inPhoto), 2);
    const Image out = renderRatio(m, photo, {}, now, inPhoto);
    EXPECT_FLOAT_EQ(out.at(0, 0)[0], 1.0f);  // the lamp: its current radiance
    EXPECT_FLOAT_EQ(out.at(1, 0)[0], 1.0f);  // enough of the lamp shows: still the lamp
    EXPECT_FLOAT_EQ(out.at(2, 0)[0], 0.3f);  // no lamp in the photo: the photo, unchanged
    EXPECT_FLOAT_EQ(out.at(3, 0)[0], 2.4f);
    // A light off in the photo shows nothing there to compare with: its face is kept.
    DisplayMap off = m;
    off.emitterFraction = {1.0f, 1.0f, 1.0f, 1.0f};
    off.unshaded = {0, 0, 0, 0};
    EXPECT_EQ(trustPhotoAtEmitters(off, photo, std::vector<Rgb>{Rgb{}}), 0);
}

namespace {

const Relighting& room() {
    return test::coarseRoom();
}

}  // namespace

TEST(RenderRatio, APixelAcrossALitAndADarkSurfaceDividesSums) {
    // One pixel, half of its samples on a lit surface (vertex 0: rho B_photo = 1, its light
    // unchanged, r = 1) and half on a dark one (vertex 1: rho B_photo = 0.01, lit 100 times
    // as much now, r = 100). The photo shows 0.505 (half of 1 + 0.01). The new pixel is half
    // of 1 + 1 = 1: the sums' ratio 2 / 1.01 times T. The plain average of the ratios would
    // give 50.5 T = 25.5025.
    DisplayMap m;
    m.width = m.height = 1;
    m.start = {0, 2};
    m.vertex = {0, 1};
    m.weight = {0.5f, 0.5f};
    m.unshaded = {0};
    m.emitterStart = {0, 0};
    packDisplayMap(m);
    Image photo(1, 1);
    for (float& v : photo.rgb) v = 0.505f;
    const std::vector<Rgb> ratio = {Rgb::gray(1), Rgb::gray(100)};
    DisplayMap weighed = m;
    weighByPhotoRadiance(weighed, std::vector<double>{1.0, 0.01});
    EXPECT_NEAR(weighed.weight[0] + weighed.weight[1], 1.0f, 1e-6f);  // the total is kept
    EXPECT_NEAR(renderRatio(weighed, photo, ratio, {}, {}).at(0, 0)[0], 1.0f, 1e-5f);
    EXPECT_NEAR(renderRatio(m, photo, ratio, {}, {}).at(0, 0)[0], 25.5025f, 1e-4f);
    // The unedited display (r = 1) is the photo whatever the weights.
    const std::vector<Rgb> one = {Rgb::gray(1), Rgb::gray(1)};
    EXPECT_FLOAT_EQ(renderRatio(weighed, photo, one, {}, {}).at(0, 0)[0], 0.505f);
    // Nothing shown in the photo at either vertex: the plain weights stay.
    DisplayMap dark = m;
    weighByPhotoRadiance(dark, std::vector<double>{0.0, 0.0});
    EXPECT_EQ(dark.weight, m.weight);
    // A value per vertex is needed.
    EXPECT_THROW(weighByPhotoRadiance(dark, std::vector<double>{1.0}), std::invalid_argument);
}

TEST(Relighting, UneditedLightsReproduceThePhoto) {
    // With real-shadow removal the texture factor is k = (D + delta) / (B + delta) at
    // every vertex (delta the display's floor), so k B/D = 1 to rounding and each pixel is
    // T times the sum of its interpolation weights (1 up to float rounding: 1e-5 relative).
    // Pixels that see a light's emitting face show its radiance instead (spec) and are
    // left out.
    const Relighting& r = room();
    const Image out = renderEdit(r.prepared, r.prepared.photoRadiance);
    double worst = 0;
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const int px = y * out.width + x;
                if (r.prepared.display.emitterStart[px] != r.prepared.display.emitterStart[px + 1])
                    continue;
                const double t = r.prepared.photo.at(x, y)[c], o = out.at(x, y)[c];
                worst = std::max(worst, std::abs(o - t) / std::max(std::abs(t), 1e-3));
            }
    EXPECT_LT(worst, 1e-5);
}

TEST(Relighting, ThePolygonsAreHeldOnceByTheSolver) {
    // The scene's polygons go to the solver rather than being copied there: the prepared
    // scene keeps none, the solver all of them, as loaded but for their reflectance.
    const SceneFile loaded = loadScene(RELIGHT_DATA_DIR "/room");
    const Relighting& r = room();
    EXPECT_TRUE(r.scene.scene.polygons.empty());
    ASSERT_EQ(r.solver->scenePolygons(), loaded.scene.polygons.size());
    ASSERT_EQ(r.solver->scene().polygons.size(), loaded.scene.polygons.size());
    for (size_t p = 0; p < loaded.scene.polygons.size(); ++p) {
        const radiosity::Polygon &a = loaded.scene.polygons[p], &b = r.solver->scene().polygons[p];
        EXPECT_EQ(a.v, b.v) << p;
        EXPECT_EQ(a.object, b.object) << p;
        EXPECT_EQ(a.light, b.light) << p;
    }
    EXPECT_EQ(r.scene.scene.lights.size(), loaded.scene.lights.size());
    EXPECT_EQ(r.scene.scene.objects, loaded.scene.objects);
}

TEST(Relighting, AllLightsOffLeavesOnlyDarkness) {
    // Every light at 0: B = 0, so each vertex ratio is delta / (D + delta) and the surfaces
    // go black, up to the guard: at most kRatioFloor x mean D / D of the photo, which over
    // the image is far below 1 % of the photo's mean.
    const Relighting& r = room();
    const std::vector<Rgb> off(r.prepared.photoRadiance.size());
    const Image out = renderEdit(r.prepared, off);
    double sumOut = 0, sumPhoto = 0;
    for (size_t i = 0; i < out.rgb.size(); ++i) {
        sumOut += static_cast<double>(out.rgb[i]);
        sumPhoto += static_cast<double>(r.prepared.photo.rgb[i]);
    }
    EXPECT_LT(sumOut, 0.01 * sumPhoto);
}

TEST(Relighting, DoublingEveryLightDoublesTheSurfaces) {
    // Linear in emittance: 2 L gives B = 2 D, a ratio of (2 D + delta) / (D + delta), 2 to
    // within delta / D = kRatioFloor x mean D / D: below 1 % wherever D is above 1 % of its
    // mean, i.e. everywhere but in deep umbra, whose pixels are dark (skipped below 1e-3).
    const Relighting& r = room();
    std::vector<Rgb> twice = r.prepared.photoRadiance;
    for (Rgb& L : twice) L = L * 2.0;
    const Image out = renderEdit(r.prepared, twice);
    const Image same = renderEdit(r.prepared, r.prepared.photoRadiance);
    int checked = 0;
    for (int px = 0; px < r.prepared.display.width * r.prepared.display.height; ++px) {
        if (r.prepared.display.emitterStart[px] != r.prepared.display.emitterStart[px + 1])
            continue;
        if (r.prepared.display.unshaded[px] > 0) continue;
        for (int c = 0; c < 3; ++c) {
            const double a = out.rgb[px * 3 + c], b = same.rgb[px * 3 + c];
            if (b < 1e-3) continue;  // dark pixels: the guard's share is not negligible
            EXPECT_NEAR(a, 2 * b, 2e-2 * b) << px;
            ++checked;
        }
    }
    EXPECT_GT(checked, 100000);
}

TEST(Relighting, RealEditsLoadAndRender) {
    const Relighting& r = room();
    const EditFile e = loadEdit(RELIGHT_DATA_DIR "/room/edits/back_off.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    const Image out = renderEdit(r.prepared, radiance);
    EXPECT_EQ(out.width, r.prepared.photo.width);
    EXPECT_EQ(out.height, r.prepared.photo.height);
    for (float v : out.rgb) ASSERT_TRUE(std::isfinite(v) && v >= 0);
}

TEST(Relighting, EditWhoseImageIsNotFiniteIsRefusedNamingItsKey) {
    const Relighting& r = room();
    const test::TempDir dir;
    // B's radiance is finite, but the relit image (photo x B/D, in float) overflows; A's
    // change is harmless, and the brightest light is the one named.
    const auto file = dir.write("huge.json", R"({"format": "relight-edit/1", "lights": {
        "A": {"scale": 2}, "B": {"radiance": [1e300, 1, 1]}}})");
    const EditFile e = loadEdit(file, r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    const Image out = renderEdit(r.prepared, radiance);
    ASSERT_FALSE(
        std::all_of(out.rgb.begin(), out.rgb.end(), [](float v) { return std::isfinite(v); }));
    try {
        requireFiniteImage(out, r.scene, e, radiance);
        ADD_FAILURE() << "a relit image that is not finite was accepted";
    } catch (const InputError& err) {
        const std::string msg = err.what();
        EXPECT_NE(msg.find(file.string() + ": key \"lights.B.radiance\": the relit image is not "
                                           "finite ("),
                  std::string::npos)
            << msg;
    }
    // The same lights at the photo's radiances: a finite image, accepted.
    const Image photoLit = renderEdit(r.prepared, r.prepared.photoRadiance);
    EXPECT_NO_THROW(requireFiniteImage(photoLit, r.scene, e, r.prepared.photoRadiance));
    // Without a radiance in the edit to blame, it is not an input error.
    try {
        requireFiniteImage(out, r.scene, EditFile{}, radiance);
        ADD_FAILURE() << "a relit image that is not finite was accepted";
    } catch (const InputError& err) {
        ADD_FAILURE() << "blamed on an edit that sets no radiance: " << err.what();
    } catch (const std::runtime_error&) {
    }
}

namespace {

/// A 4 x 3 x 2.5 m room, faces inward, and its scene.json with "Lamp" under the ceiling,
/// facing down into it, followed by `moreLights` (JSON, each with a leading comma).
void writeLampRoom(const test::TempDir& dir, const std::string& moreLights) {
    dir.write("room.obj",
              "v 0 0 0\nv 4 0 0\nv 4 3 0\nv 0 3 0\nv 0 0 2.5\nv 4 0 2.5\nv 4 3 2.5\nv 0 3 2.5\n"
              "o room\nf 1 2 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n");
    dir.write("scene.json", R"({
      "format": "relight-scene/1",
      "geometry": ["room.obj"],
      "camera": {"width": 64, "height": 48, "K": [[50, 0, 31.5], [0, 50, 23.5], [0, 0, 1]],
                 "world_to_camera": [[1, 0, 0, -2], [0, -1, 0, 1.5], [0, 0, -1, 2.4]]},
      "lights": [
        {"name": "Lamp", "type": "quad", "radiance": [10, 10, 10],
         "vertices": [[1.1, 1.1, 2.45], [1.4, 1.1, 2.45], [1.4, 0.8, 2.45], [1.1, 0.8, 2.45]]})" +
                                moreLights + "]}");
}

}  // namespace

TEST(LightReachWarnings, ALampBelowTheFloorIsNamedAndOneInTheRoomIsNot) {
    // A 4 x 3 x 2.5 m room, faces inward; "Lamp" under the ceiling faces down into it, "Under"
    // lies below the floor facing up at its back. Only the solver's scene is needed.
    const test::TempDir dir;
    writeLampRoom(dir, R"(,
        {"name": "Under", "type": "quad", "radiance": [10, 10, 10],
         "vertices": [[1.1, 0.8, -0.2], [1.4, 0.8, -0.2], [1.4, 1.1, -0.2], [1.1, 1.1, -0.2]]})");
    const SceneFile sf = loadScene(dir.path());
    const radiosity::HierarchicalSolver solver(sf.scene, radiosity::SolverOptions{});
    const std::vector<std::string> warnings =
        lightReachWarnings(sf, solver.scene(), solver.visibility());
    ASSERT_EQ(warnings.size(), 1u);
    const std::string& w = warnings[0];
    EXPECT_NE(w.find((dir.path() / "scene.json").string() +
                     ": key \"lights[1]\": light \"Under\": "
                     "its emitting side sees no part of the scene"),
              std::string::npos)
        << w;
    EXPECT_EQ(w.find("Lamp"), std::string::npos) << w;

    // Moved above the floor, facing down at it, it is not reported.
    dir.write("scene.json", [&] {
        std::ifstream in(dir.path() / "scene.json");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string up =
            "[[1.1, 0.8, -0.2], [1.4, 0.8, -0.2], [1.4, 1.1, -0.2], [1.1, 1.1, -0.2]]";
        text.replace(text.find(up), up.size(),
                     "[[1.1, 1.1, 0.2], [1.4, 1.1, 0.2], [1.4, 0.8, 0.2], [1.1, 0.8, 0.2]]");
        return text;
    }());
    const SceneFile moved = loadScene(dir.path());
    const radiosity::HierarchicalSolver solver2(moved.scene, radiosity::SolverOptions{});
    EXPECT_TRUE(lightReachWarnings(moved, solver2.scene(), solver2.visibility()).empty());
}

TEST(LightReachWarnings, AVirtualLightFacingAwayIsNamedByItsEditKey) {
    // The same room with one lamp; an edit adds two virtual lights facing down: "In" under
    // the ceiling, "Away" above it, where it sees only the ceiling's back. Only "Away" is
    // reported, with the edit's file and key; the solver holds both (as after insertion).
    const test::TempDir dir;
    writeLampRoom(dir, "");
    dir.write("edit.json", R"({
      "format": "relight-edit/1",
      "add_lights": [
        {"name": "In", "type": "quad", "radiance": [5, 5, 5],
         "vertices": [[2.1, 1.6, 2.4], [2.4, 1.6, 2.4], [2.4, 1.3, 2.4], [2.1, 1.3, 2.4]]},
        {"name": "Away", "type": "quad", "radiance": [5, 5, 5],
         "vertices": [[2.1, 1.6, 2.7], [2.4, 1.6, 2.7], [2.4, 1.3, 2.7], [2.1, 1.3, 2.7]]}
      ]})");
    const SceneFile sf = loadScene(dir.path());
    const EditFile edit = loadEdit(dir.path() / "edit.json", sf);
    radiosity::HierarchicalSolver solver(sf.scene, radiosity::SolverOptions{});
    solver.solve();
    for (const VirtualLight& v : edit.addLights) {
        std::vector<radiosity::Vec3> corners(v.corners.begin(), v.corners.end());
        solver.insertObject(v.name, {radiosity::makePolygon(corners, -1, radiosity::Rgb{})},
                            &v.radiance);
    }
    const std::vector<std::string> warnings =
        virtualLightReachWarnings(edit, solver.scene(), solver.visibility(), 1);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find((dir.path() / "edit.json").string() +
                               ": key \"add_lights[1]\": light \"Away\": its emitting side sees"),
              std::string::npos)
        << warnings[0];
    // Before the parts are inserted there is nothing to look at: no warning, no crash.
    const radiosity::HierarchicalSolver bare(sf.scene, radiosity::SolverOptions{});
    EXPECT_TRUE(virtualLightReachWarnings(edit, bare.scene(), bare.visibility(), 1).empty());
}

namespace {

/// A copy of the room whose photo is replaced by `photo`.
std::string roomWithPhoto(const relight::test::TempDir& dir, const Image& photo) {
    namespace fs = std::filesystem;
    const fs::path src = RELIGHT_DATA_DIR "/room";
    for (const char* f : {"scene.json", "room.obj", "photo.mask.png"})
        fs::copy_file(src / f, dir.path() / f, fs::copy_options::overwrite_existing);
    writeImage(dir.path() / "photo.exr", photo);
    return dir.path().string();
}

std::string prepareError(const std::string& sceneDir) {
    try {
        prepareRelighting(loadScene(sceneDir), {});
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Relighting, PhotoOfTheWrongSizeIsAnError) {
    relight::test::TempDir dir("relight_photo_test");
    const std::string scene = roomWithPhoto(dir, Image(32, 24));
    const std::string msg = prepareError(scene);
    EXPECT_NE(msg.find("photo.exr: photo is 32x24 but the camera is 320x240"), std::string::npos)
        << msg;
}

TEST(Relighting, NonFinitePixelIsAnErrorNamingThePixel) {
    relight::test::TempDir dir("relight_photo_test");
    Image photo = room().prepared.photo;
    photo.at(17, 5)[1] = std::numeric_limits<float>::quiet_NaN();
    const std::string msg = prepareError(roomWithPhoto(dir, photo));
    EXPECT_NE(msg.find("photo.exr: pixel (17, 5) is not a finite number"), std::string::npos)
        << msg;
}

TEST(Relighting, LightOffInThePhotoCanBeSwitchedOn) {
    // The room with lamp D said to be off in its photo (the photo itself is unchanged: only
    // the bookkeeping matters here). An edit "D": {"scale": 1} must bring D in at its
    // scene.json radiance, and the relit image must brighten where D shines: the vertex
    // irradiance gains exactly D's response (superposition), so no vertex gets darker and
    // the image's total rises.
    namespace fs = std::filesystem;
    relight::test::TempDir dir("relight_off_test");
    const fs::path src = RELIGHT_DATA_DIR "/room";
    for (const char* f : {"room.obj", "photo.exr", "photo.mask.png"})
        fs::copy_file(src / f, dir.path() / f);
    nlohmann::json scene;
    std::ifstream(src / "scene.json") >> scene;
    auto& on = scene["photos"][0]["lights_on"];
    on.erase(std::remove(on.begin(), on.end(), "D"), on.end());
    dir.write("scene.json", scene.dump());
    RelightOptions o;
    o.epsilon = 1e-3;
    o.spp = 1;
    o.reflectanceRounds = 1;
    const auto r = prepareRelighting(loadScene(dir.path()), o);
    const int d = r->scene.scene.findLight("D");
    ASSERT_GE(d, 0);
    EXPECT_EQ(r->prepared.photoRadiance[d], Rgb{});
    const EditFile e = loadEdit(dir.write("on.json", R"({"format":"relight-edit/1",
        "lights":{"D":{"scale":1}}})"),
                                r->scene);
    const auto radiance = editRadiance(r->scene, e, r->prepared.photoRadiance);
    EXPECT_EQ(radiance[d], r->scene.nominalRadiance[d]);
    ASSERT_GT(radiance[d].maxComponent(), 0.0);
    const auto before = vertexIrradiance(r->prepared, r->prepared.photoRadiance);
    const auto after = vertexIrradiance(r->prepared, radiance);
    for (size_t v = 0; v < before.size(); ++v)
        for (int c = 0; c < 3; ++c) ASSERT_GE(after[v][c], before[v][c]);
    const Image lit = renderEdit(r->prepared, radiance),
                same = renderEdit(r->prepared, r->prepared.photoRadiance);
    double sumLit = 0, sumSame = 0;
    for (size_t i = 0; i < lit.rgb.size(); ++i) {
        sumLit += static_cast<double>(lit.rgb[i]);
        sumSame += static_cast<double>(same.rgb[i]);
    }
    EXPECT_GT(sumLit, 1.05 * sumSame);
}

TEST(ShadowRemoval, RegionsFrontierAndReferencesFollowThePaper) {
    // §4.3-4.4 on the room (three lamps, furniture casting shadows): the classes, the
    // frontier and the reference choice obey their definitions, and the corrections their
    // bounds.
    const Relighting& r = room();
    const ShadowRemoval& sr = r.removal;
    const auto& h = r.solver->hierarchy();
    ASSERT_GT(sr.occluded, 0);
    ASSERT_GT(sr.frontier, 0);
    int frontier = 0;
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        if (sr.leafClass[n] == LeafShadowClass::frontier) {
            ++frontier;  // a lit leaf with an occluded edge neighbour (Fig. 14(a))
            const auto nb = h.edgeNeighbours(n);
            EXPECT_TRUE(std::any_of(nb.begin(), nb.end(), [&](int m) {
                return sr.leafClass[m] == LeafShadowClass::occluded;
            }));
        }
        const int ref = sr.reference[n];
        if (ref < 0 || ref == n) continue;
        // Fig. 15 / Eq. (10): the reference is on the frontier and brighter in every
        // channel; Eq. (11): the correction never darkens.
        EXPECT_EQ(sr.leafClass[n], LeafShadowClass::occluded);
        EXPECT_EQ(sr.leafClass[ref], LeafShadowClass::frontier);
        const Rgb ci = r.texture->colour(n), cr = r.texture->colour(ref);
        for (int c = 0; c < 3; ++c) {
            EXPECT_LT(ci[c], cr[c]);
            EXPECT_GE(sr.rhoRatio[n][c], 1.0);
        }
    }
    EXPECT_EQ(frontier, sr.frontier);
    const size_t nv = sr.blocked.size();
    ASSERT_EQ(nv, r.mesh->vertices().size());
    for (size_t v = 0; v < nv; ++v)
        for (int c = 0; c < 3; ++c) {
            EXPECT_GE(sr.blocked[v][c], 0.0);         // Eq. (8): blocked light is not negative
            EXPECT_GE(sr.linkCorrection[v][c], 0.0);  // Eq. (15), clamped to [0, D0 / Dv]
            EXPECT_GE(sr.D[v][c], 0.0);
            EXPECT_TRUE(std::isfinite(sr.kFinal[v][c]) && sr.kFinal[v][c] > 0);
        }
}
