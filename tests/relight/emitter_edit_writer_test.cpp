// Tests of saving the edits of suns, point lamps and skies (relight/io/edit_writer.h with
// radiosity::Emitter::fields/editFields): every edit field of docs/scene-format.md ("Edit":
// scale, irradiance, intensity, sh9, direction, position, rotate, add_lights of sun, point
// and environment) on data/courtyard (a sun and a sky) and on a scene with a real point lamp,
// saved into another folder, loads back to the same light state: the same strengths of every
// scene light (editedRadiance), the same moved lights and virtual lights, field by field.
// The equalities are exact: saving only copies numbers (nlohmann writes the shortest text
// that reads back as the same double) and a sun's direction is written as it was given.
#include "radiosity/emitter.h"
#include "relight/io/edit_writer.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using radiosity::Rgb;
using relight::EditFile;
using relight::loadEdit;
using relight::SceneFile;
using relight::VirtualLight;
using relight::test::TempDir;

const fs::path kCourtyard = fs::path(RELIGHT_DATA_DIR) / "courtyard";

const SceneFile& courtyard() {
    static const SceneFile sf = relight::loadScene(kCourtyard);
    return sf;
}

/// Every number of a light's fields, with its type: two lights with equal lists say the same.
std::vector<std::pair<std::string, std::vector<double>>> describe(const radiosity::Emitter& e) {
    std::vector<std::pair<std::string, std::vector<double>>> out{{e.type(), {}}};
    for (const radiosity::EmitterField& f : e.fields()) out.emplace_back(f.key, f.values);
    return out;
}

void expectSameLights(const std::vector<VirtualLight>& a, const std::vector<VirtualLight>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].name, b[i].name);
        ASSERT_EQ(a[i].emitter != nullptr, b[i].emitter != nullptr) << a[i].name;
        if (a[i].emitter) {
            EXPECT_EQ(describe(*a[i].emitter), describe(*b[i].emitter)) << a[i].name;
        } else {
            EXPECT_EQ(a[i].corners, b[i].corners) << a[i].name;
            EXPECT_TRUE(a[i].radiance == b[i].radiance) << a[i].name;
        }
    }
}

/// `edit` saved into another folder and loaded again gives the same light state; saved a
/// second time, the same text (the writer is a fixed point of its own output).
void expectRoundTrip(const SceneFile& sf, const fs::path& edit) {
    SCOPED_TRACE(edit.string());
    const EditFile a = loadEdit(edit, sf);
    TempDir dir("emitter_edit_writer");
    const fs::path saved = dir.path() / "saved.json";
    relight::writeEdit(saved, a);
    const EditFile b = loadEdit(saved, sf);
    const std::vector<Rgb> ra = relight::editedRadiance(sf, a, sf.nominalRadiance);
    const std::vector<Rgb> rb = relight::editedRadiance(sf, b, sf.nominalRadiance);
    ASSERT_EQ(ra.size(), rb.size());
    for (size_t i = 0; i < ra.size(); ++i)
        EXPECT_TRUE(ra[i] == rb[i])
            << "light " << sf.scene.lights[i].name << " component " << sf.scene.lights[i].component;
    expectSameLights(relight::movedLights(sf, a), relight::movedLights(sf, b));
    expectSameLights(a.addLights, b.addLights);
    EXPECT_EQ(relight::editJson(a, dir.path()), relight::editJson(b, dir.path()));
}

TEST(EmitterEditWriter, EveryCourtyardEditRoundTrips) {
    for (const auto& entry : fs::directory_iterator(kCourtyard / "edits"))
        if (entry.path().extension() == ".json") expectRoundTrip(courtyard(), entry.path());
}

TEST(EmitterEditWriter, EveryFieldOfASunASkyAndAddedLightsRoundTrips) {
    TempDir dir("emitter_edit_fields");
    // Each field the format gives these lights, with numbers that are not short decimals.
    const json edit = {
        {"format", "relight-edit/1"},
        {"lights",
         {{"sun",
           {{"irradiance", {3.1, 2.7, 1.0 / 3}}, {"scale", 0.7}, {"direction", {0.1, -0.3, 0.9}}}},
          {"sky",
           {{"sh9", json::array({{0.4, 0.5, 0.6},
                                 {-0.1, -0.2, -0.3},
                                 {0.2, 0.2, 0.2},
                                 {0, 0, 0},
                                 {0.01, 0.02, 0.03},
                                 {0, 0, 0},
                                 {-0.05, -0.05, 0},
                                 {0, 0.1, 0},
                                 {0.3, 0, -0.3}})},
            {"rotate", {{"axis", {0.2, 0.1, 1}}, {"degrees", 37.5}}},
            {"scale", 1.25}}}}},
        {"add_lights", json::array({{{"name", "sun2"},
                                     {"type", "sun"},
                                     {"direction", {-0.2, 0.4, 2.0}},
                                     {"angle", 1.7},
                                     {"irradiance", {1, 0.5, 0.25}}},
                                    {{"name", "P1"},
                                     {"type", "point"},
                                     {"position", {0.8, 3.6, 2.8}},
                                     {"intensity", {6.0, 5.2, 4.0 / 7}}},
                                    {{"name", "sky2"},
                                     {"type", "environment"},
                                     {"sh9", json::array({{0.1, 0.1, 0.1},
                                                          {0, 0, 0},
                                                          {0.05, 0.05, 0.05},
                                                          {0, 0, 0},
                                                          {0, 0, 0},
                                                          {0, 0, 0},
                                                          {0, 0, 0},
                                                          {0, 0, 0},
                                                          {0, 0, 0}})}},
                                    {{"name", "Q1"},
                                     {"type", "quad"},
                                     {"vertices", {{0, 0, 3}, {1, 0, 3}, {1, 1, 3}, {0, 1, 3}}},
                                     {"radiance", {2, 2, 2}}}})}};
    std::ofstream(dir.path() / "all.json") << edit.dump(1);
    expectRoundTrip(courtyard(), dir.path() / "all.json");

    // The saved file says each part with the keys of its light's type.
    const EditFile a = loadEdit(dir.path() / "all.json", courtyard());
    const json saved = relight::editJson(a, dir.path());
    EXPECT_TRUE(saved["lights"]["sun"].contains("irradiance"));
    EXPECT_TRUE(saved["lights"]["sun"].contains("direction"));
    EXPECT_FALSE(saved["lights"]["sun"].contains("radiance"));
    EXPECT_EQ(saved["lights"]["sky"]["rotate"]["degrees"], 37.5);
    EXPECT_EQ(saved["lights"]["sky"]["sh9"].size(), 9u);
    EXPECT_EQ(saved["add_lights"][0]["type"], "sun");
    EXPECT_EQ(saved["add_lights"][0]["angle"], 1.7);
    EXPECT_EQ(saved["add_lights"][1]["intensity"][2], 4.0 / 7);
    EXPECT_EQ(saved["add_lights"][2]["type"], "environment");
    EXPECT_EQ(saved["add_lights"][3]["type"], "quad");
}

/// data/courtyard with a real point lamp "lamp" added to scene.json (its files referred to
/// by absolute paths), loaded.
SceneFile courtyardWithLamp(const TempDir& dir) {
    std::ifstream in(kCourtyard / "scene.json");
    json scene = json::parse(in);
    for (json& g : scene["geometry"]) g = (kCourtyard / g.get<std::string>()).string();
    for (json& p : scene["photos"]) {
        p["file"] = (kCourtyard / p["file"].get<std::string>()).string();
        p["lights_on"].push_back("lamp");
    }
    scene["lights"].push_back({{"name", "lamp"},
                               {"type", "point"},
                               {"position", {1.2, 2.5, 2.2}},
                               {"intensity", {4.0, 3.5, 3.0}}});
    std::ofstream(dir.path() / "scene.json") << scene.dump(1);
    return relight::loadScene(dir.path());
}

TEST(EmitterEditWriter, APointLampsIntensityPositionAndScaleRoundTrip) {
    TempDir dir("emitter_edit_lamp");
    const SceneFile sf = courtyardWithLamp(dir);
    ASSERT_GE(sf.scene.findLight("lamp"), 0);
    const std::vector<json> edits = {
        {{"lamp", {{"position", {2.0 / 3, 3.1, 1.9}}}}},
        {{"lamp", {{"intensity", {1.5, 1.0, 0.1}}, {"scale", 3.0}}}},
        {{"lamp", {{"scale", 0.0}}}, {"sun", {{"scale", 0.0}}}},
        {{"lamp", {{"position", {0.5, 1.5, 2.5}}, {"intensity", {2, 2, 2}}}},
         {"sky", {{"rotate", {{"axis", {0, 0, 1}}, {"degrees", -90}}}}}}};
    for (size_t i = 0; i < edits.size(); ++i) {
        const fs::path file = dir.path() / ("lamp" + std::to_string(i) + ".json");
        std::ofstream(file) << json{{"format", "relight-edit/1"}, {"lights", edits[i]}}.dump(1);
        expectRoundTrip(sf, file);
    }
}

TEST(EmitterEditWriter, AnEmitterEditWithoutItsLightIsRefusedNamingTheKey) {
    // The writer cannot tell "irradiance" from "intensity" without the light.
    EditFile e;
    relight::LightEdit le;
    le.emitter = radiosity::EmitterEdit{};
    le.emitter->strength = Rgb{1, 1, 1};
    e.lights["sun"] = le;
    try {
        relight::editJson(e, {});
        FAIL() << "no error";
    } catch (const std::invalid_argument& ex) {
        EXPECT_NE(std::string(ex.what()).find("lights.sun"), std::string::npos) << ex.what();
    }
}

TEST(EmitterEditWriter, FieldsReadBackToTheSameLight) {
    // Emitter::fields() is what the light reader reads: each type made, written as an
    // add_lights entry, loaded, gives the same fields.
    TempDir dir("emitter_fields");
    EditFile e;
    e.lights.clear();
    e.addLights.push_back({"s", {}, {}, radiosity::makeSun("s", {0.3, 0.2, 0.1}, 0.53, {7, 6, 5})});
    e.addLights.push_back({"p", {}, {}, radiosity::makePointLamp("p", {1, 2, 3}, {1, 2, 4})});
    radiosity::Sh9Rgb L;
    for (int k = 0; k < radiosity::kSh9Count; ++k)
        L.c[static_cast<size_t>(k)] = Rgb{0.1 * k, -0.01 * k, 0.3};
    e.addLights.push_back({"e", {}, {}, radiosity::makeEnvironment("e", L)});
    relight::writeEdit(dir.path() / "lights.json", e);
    const EditFile back = loadEdit(dir.path() / "lights.json", courtyard());
    expectSameLights(e.addLights, back.addLights);
}

}  // namespace
