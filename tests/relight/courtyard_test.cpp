// The bundled courtyard (data/courtyard): a paved court between three walls, open to the
// sky, lit by a sun and an SH9 sky (Cycles ground truth, 1024 spp). Its lights load as the
// light model's components, and edits of the sun and the sky match the truth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>
#include <sstream>
#include <string>

#include "radiosity/emitter.h"
#include "relight/display/metric.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/errors.h"
#include "relight/io/edit_file.h"
#include "relight/io/scene_file.h"
#include "relight/prepared.h"
#include "relight/relighting.h"
#include "room_fixture.h"

using namespace relight;
namespace fs = std::filesystem;

namespace {

const std::string kCourtyard = RELIGHT_DATA_DIR "/courtyard";

/// The settings of `relight render` (the per-pixel light, 16 samples per pixel): the
/// tests' coarse ones (4 samples) leave the sun's shadow edges twice as noisy per pixel
/// (sun_moved 0.057 against 0.028), beyond the bound below. Prepared once (7 s).
Relighting& courtyard() {
    static const auto r = [] {
        RelightOptions o;
        o.pixelLight = true;
        return prepareRelighting(loadScene(kCourtyard), o);
    }();
    return *r;
}

// The truth's own noise: truth/identity.exr against photo.exr, both Cycles renders of the
// same light, differ by rel_rmse 0.0064 (data/courtyard/README.md). The issue's bound for a
// light edit, 0.03, is about 5 times that floor: what the engine may add to the noise.
constexpr double kLightEditBound = 0.03;

}  // namespace

TEST(Courtyard, ASunAndASkyAndEveryEditLoad) {
    const SceneFile sf = loadScene(kCourtyard);
    ASSERT_EQ(sf.scene.lights.size(), 10u);  // the sun, the sky's 9 coefficients
    EXPECT_STREQ(sf.scene.lights[0].emitter->type(), "sun");
    EXPECT_STREQ(sf.scene.lights[1].emitter->type(), "environment");
    int edits = 0;
    for (const auto& entry : fs::directory_iterator(kCourtyard + "/edits")) {
        SCOPED_TRACE(entry.path().string());
        loadEdit(entry.path(), sf);
        ++edits;
    }
    EXPECT_EQ(edits, 9);
}

TEST(Courtyard, TheSunOffAndTheSkyTurnedMatchTheTruth) {
    // Both are changes of strength only (the sky turned is new coefficients): a weighted
    // sum of the per-light responses and per-pixel direct light.
    const Relighting& r = courtyard();
    for (const char* name : {"sun_off", "sky_rotated"}) {
        const EditFile e = loadEdit(kCourtyard + "/edits/" + name + ".json", r.scene);
        const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
        const Score s = test::scoreAgainstTruth(
            kCourtyard, name, renderEdit(r.prepared, radiance, DisplayMode::pixel),
            r.prepared.photo);
        std::printf("%s, pixel display: rel_rmse %.4f, changed %.4f\n", name, s.relRmse,
                    s.changedRelRmse);
        EXPECT_LE(s.relRmse, kLightEditBound) << name;
    }
}

TEST(Courtyard, TheSunMovedMatchesTheTruth) {
    // The sun turned: off where it was, a virtual sun where it went (movedLights()), its
    // new shadows measured per pixel and its bounces gathered by the solver.
    Relighting& r = courtyard();
    const EditFile e = loadEdit(kCourtyard + "/edits/sun_moved.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    Image image;
    {
        DynamicRelighting dyn(r, radiance);  // gives the solver back as prepared
        for (const VirtualLight& l : movedLights(r.scene, e)) dyn.addLight(l);
        image = dyn.render(DisplayMode::pixel);
    }
    const Score s = test::scoreAgainstTruth(kCourtyard, "sun_moved", image, r.prepared.photo);
    std::printf("sun_moved, pixel display: rel_rmse %.4f, changed %.4f\n", s.relRmse,
                s.changedRelRmse);
    EXPECT_LE(s.relRmse, kLightEditBound);
}

TEST(Courtyard, AMovedSunsQuickDirectLightIsTheExactOneAwayFromItsShadowEdges) {
    // The quick frames of a sun drag (DynamicRelighting::previewEmitter,
    // relight/dynamic/quick_light.h): one camera sample and one shadow ray per pixel, against
    // the exact per-pixel light of the same moved sun (16 samples x 16 disc rays), both
    // from one instance (the same solver and virtual sun).
    Relighting& r = courtyard();
    const EditFile e = loadEdit(kCourtyard + "/edits/sun_moved.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    const std::vector<VirtualLight> moved = movedLights(r.scene, e);
    ASSERT_EQ(moved.size(), 1u);
    const auto d = radiosity::findField(*moved[0].emitter, "direction");
    ASSERT_TRUE(d.has_value());
    const radiosity::Vec3 sun =
        glm::normalize(radiosity::Vec3(d->values[0], d->values[1], d->values[2]));
    DynamicRelighting dyn(r, radiance);
    const int light = dyn.addLight(moved[0]);
    const size_t L = dyn.radiance().size(), pixels = r.prepared.pixelNormal.size() / 3;
    std::vector<double> exact(pixels), quick(pixels);
    std::span<const float> all = dyn.pixelDirect();
    for (size_t px = 0; px < pixels; ++px) exact[px] = all[px * L + static_cast<size_t>(light)];
    EXPECT_FALSE(dyn.previewing());
    dyn.previewEmitter(light, *moved[0].emitter);
    EXPECT_TRUE(dyn.previewing());
    all = dyn.pixelDirect();
    for (size_t px = 0; px < pixels; ++px) quick[px] = all[px * L + static_cast<size_t>(light)];
    // Where the exact light is whole (every ray of every sample reaches the disc: cos of the
    // pixel's normal) or none (every ray blocked), one ray tells the same. The tolerance is
    // the disc's spread: its radius, 0.27 degrees (the format's default sun), moves cos by
    // at most sin(0.0047) = 0.0047 per unit irradiance; 0.01 leaves room for a pixel's
    // samples on slightly different normals.
    size_t whole = 0, none = 0, wrong = 0, edge = 0;
    double sumExact = 0, sumQuick = 0;
    for (size_t px = 0; px < pixels; ++px) {
        const std::vector<float>& normal = r.prepared.pixelNormal;
        const radiosity::Vec3 n(normal[3 * px], normal[3 * px + 1], normal[3 * px + 2]);
        const double cosine = std::max(0.0, glm::dot(n, sun));
        sumExact += exact[px];
        sumQuick += quick[px];
        const bool isWhole = cosine > 0.05 && std::abs(exact[px] - cosine) <= 1e-3;
        const bool isNone = exact[px] == 0.0;
        if (!isWhole && !isNone) {
            ++edge;
            continue;
        }
        (isWhole ? whole : none) += 1;
        if (std::abs(quick[px] - exact[px]) > 0.01) ++wrong;
    }
    std::printf(
        "moved sun, %zu pixels: %zu lit whole, %zu in shadow, %zu between; quick != exact "
        "at %zu of the whole or none; mean %.4f quick, %.4f exact\n",
        pixels, whole, none, edge, wrong, sumQuick / static_cast<double>(pixels),
        sumExact / static_cast<double>(pixels));
    EXPECT_GT(whole, pixels / 4) << "the moved sun lights a good part of the courtyard";
    EXPECT_GT(none, pixels / 20) << "and casts shadows";
    // A disc direction of the quick ray that the 256 exact rays missed: a blocker's sliver.
    EXPECT_LE(wrong, (whole + none) / 500);
    // Over the image, the edges' 0-or-1 values average out (the quick ray's direction is
    // uniform over the disc, its sample one of the pixel's): the mean within 1 %.
    EXPECT_NEAR(sumQuick, sumExact, 0.01 * sumExact);
}

TEST(Courtyard, AMovedSunsFrameIsAFunctionOfItsDirectLightAlone) {
    // DynamicRelighting::movedLightFrame: the per-pixel display of a sun being moved as
    // scale * out(g) + offset, g the sun's unit irradiance per pixel, which the viewer's GPU
    // measures from a shadow map at each frame. Given the quick frame's own g (its one ray
    // per pixel), it must give the quick frame's image: the same sums, regrouped, in float
    // where render() sums in double (relative rounding about 1e-6; 1e-4 of the image's
    // largest value allows a sum of tens of float terms).
    Relighting& r = courtyard();
    const EditFile e = loadEdit(kCourtyard + "/edits/sun_moved.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    const std::vector<VirtualLight> moved = movedLights(r.scene, e);
    ASSERT_EQ(moved.size(), 1u);
    DynamicRelighting dyn(r, radiance);
    const int light = dyn.addLight(moved[0]);
    // Turned further, shown quickly (the frames of a drag).
    std::unique_ptr<radiosity::Emitter> turned = moved[0].emitter->clone();
    radiosity::EmitterEdit turn;
    turn.direction = radiosity::Vec3{0.3, -0.5, 0.8};
    turned->apply(turn);
    dyn.previewEmitter(light, *turned);
    const Image quick = dyn.render(DisplayMode::pixel);
    const std::optional<MovedLightFrame> f = dyn.movedLightFrame(light);
    ASSERT_TRUE(f.has_value());
    EXPECT_EQ(f->source.kind, radiosity::ShadowSource::Kind::direction);
    EXPECT_NEAR(glm::dot(f->source.at, glm::normalize(*turn.direction)), 1.0, 1e-12);
    const size_t L = dyn.radiance().size(), pixels = f->terms.drawn.size();
    const std::span<const float> direct = dyn.pixelDirect();
    float top = 0;
    for (float v : quick.rgb) top = std::max(top, v);
    double worst = 0;
    size_t drawn = 0;
    for (size_t px = 0; px < pixels; ++px) {
        float out[3] = {0, 0, 0};
        if (f->terms.drawn[px]) {
            ++drawn;
            evalPixelLightTerms(f->terms, px, direct[px * L + static_cast<size_t>(light)], out);
        }
        for (size_t c = 0; c < 3; ++c) {
            const float v = f->scale[3 * px + c] * out[c] + f->offset[3 * px + c];
            worst = std::max(worst, static_cast<double>(std::abs(v - quick.rgb[3 * px + c])));
        }
    }
    std::printf(
        "moved sun's frame from its terms: %zu of %zu pixels drawn per pixel; worst "
        "difference %.3g (image max %.3g)\n",
        drawn, pixels, worst, static_cast<double>(top));
    EXPECT_GT(drawn, pixels / 2);
    EXPECT_LE(worst, 1e-4 * static_cast<double>(top));
    // A sky has no one direction: no such frame.
    EXPECT_FALSE(dyn.movedLightFrame(1).has_value());
}

TEST(Courtyard, WensDisplayOfASessionWithoutPartsIsTheLightEdit) {
    // DynamicRelighting's wen display (relight/display/wen_display.h) with no virtual part:
    // the photo's direct light per pixel and no indirect change, so the light edit's sums
    // (1e-6: float rounding of the same terms, as the pixel display's test in
    // dynamic_relighting_test.cpp).
    Relighting& r = courtyard();
    const EditFile e = loadEdit(kCourtyard + "/edits/sky_rotated.json", r.scene);
    const auto radiance = editRadiance(r.scene, e, r.prepared.photoRadiance);
    const Image edit = renderEdit(r.prepared, radiance, DisplayMode::wen);
    double diff = 0, changed = 0;
    {
        DynamicRelighting dyn(r, radiance);
        const Image session = dyn.render(DisplayMode::wen);
        for (size_t i = 0; i < edit.rgb.size(); ++i) {
            diff = std::max(diff, static_cast<double>(std::abs(session.rgb[i] - edit.rgb[i])));
            changed = std::max(
                changed, static_cast<double>(std::abs(edit.rgb[i] - r.prepared.photo.rgb[i])));
        }
    }
    EXPECT_LE(diff, 1e-6);
    EXPECT_GT(changed, 0.01) << "the sky turned changed nothing";
}

namespace {

EditFile editOf(const SceneFile& sf, const std::string& text) {
    std::istringstream in(text);
    return parseEdit(in, kCourtyard + "/edits/test.json", sf);
}

std::string editError(const SceneFile& sf, const std::string& text) {
    try {
        editOf(sf, text);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Courtyard, EditsOfTheSunAndTheSkyGiveTheirStrengthsOrMoveThem) {
    const SceneFile sf = loadScene(kCourtyard);
    // The sky turned: its 9 lights get the coefficients of the turned sky
    // (radiosity::sh9RotateAboutAxis, tested against closed forms in sh9_test.cpp).
    const EditFile turn = editOf(
        sf,
        R"({"format": "relight-edit/1", "lights": {"sky": {"rotate": {"axis": [0, 0, 1], "degrees": 120}}}})");
    const std::vector<Rgb> r = editedRadiance(sf, turn, sf.nominalRadiance);
    radiosity::Sh9Rgb sky;
    for (int k = 0; k < 9; ++k) sky.c[static_cast<size_t>(k)] = sf.nominalRadiance[1 + k];
    const radiosity::Sh9Rgb want = radiosity::sh9RotateAboutAxis(sky, {0, 0, 1}, 120);
    for (int k = 0; k < 9; ++k)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(r[1 + k][c], want.c[static_cast<size_t>(k)][c]) << k;
    EXPECT_EQ(r[0].r, sf.nominalRadiance[0].r);  // the sun as in the photo
    EXPECT_TRUE(movedLights(sf, turn).empty());

    // The sun turned and scaled: off where it was, one virtual sun at the new direction
    // with the scaled irradiance.
    const EditFile move = editOf(
        sf,
        R"({"format": "relight-edit/1", "lights": {"sun": {"direction": [0, 0, 1], "scale": 0.5}}})");
    EXPECT_EQ(editedRadiance(sf, move, sf.nominalRadiance)[0].r, 0.0);
    const std::vector<VirtualLight> moved = movedLights(sf, move);
    ASSERT_EQ(moved.size(), 1u);
    EXPECT_EQ(moved[0].emitter->strengths()[0].r, 0.5 * sf.nominalRadiance[0].r);
    // Straight up: a floor (normal +z) gets the whole (scaled) irradiance, unoccluded.
    EXPECT_NEAR(moved[0].emitter->unoccludedIrradiance({{0, 0, 0}, {0, 0, 1}, -1}).r,
                0.5 * sf.nominalRadiance[0].r, 1e-12);

    // A field the light's type lacks, named with the light and the key.
    EXPECT_NE(
        editError(sf, R"({"format": "relight-edit/1", "lights": {"sun": {"position": [0, 0, 1]}}})")
            .find("key \"lights.sun\": light 'sun' (sun) has no position"),
        std::string::npos);
    EXPECT_NE(
        editError(sf, R"({"format": "relight-edit/1", "lights": {"sky": {"radiance": [1, 1, 1]}}})")
            .find("key \"lights.sky.radiance\": unknown key"),
        std::string::npos);
    EXPECT_NE(
        editError(
            sf,
            R"({"format": "relight-edit/1", "lights": {"sky": {"rotate": {"axis": [0, 0, 0], "degrees": 90}}}})")
            .find("key \"lights.sky\""),
        std::string::npos);
}
