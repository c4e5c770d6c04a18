// Tests of edit loading (relight/io/edit_file.h): every bundled edit of data/room, the
// radiance an edit gives each real light (exact equalities: an edit only copies or scales
// numbers), and one bad input per error class, each of which must raise an InputError
// naming the edit file and the key path.
#include "relight/io/edit_file.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using radiosity::Rgb;
using relight::editedRadiance;
using relight::EditFile;
using relight::InputError;
using relight::loadEdit;
using relight::SceneFile;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

using relight::test::TempDir;

const fs::path kRoom = fs::path(RELIGHT_DATA_DIR) / "room";

/// data/room, loaded once: loading solves nothing but reads the OBJ.
const SceneFile& room() {
    static const SceneFile sf = relight::loadScene(kRoom);
    return sf;
}

EditFile loadRoomEdit(const std::string& name) {
    return loadEdit(kRoom / "edits" / (name + ".json"), room());
}

size_t lightIndex(const SceneFile& sf, const std::string& name) {
    const int i = sf.scene.findLight(name);
    EXPECT_GE(i, 0) << name;
    return static_cast<size_t>(i);
}

/// The InputError's message for `f`; fails the test when `f` throws none.
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return {};
}

// ---- the bundled edits -----------------------------------------------------------------

const std::vector<std::string> kLightsOnly = {"identity", "back_off", "colours",
                                              "left_off_right_double", "right_off_left_double"};
const std::vector<std::string> kLater = {
    "virtual_box",  "virtual_box_moved", "virtual_light_and_box", "virtual_light_only",
    "remove_table", "remove_cabinet",    "virtual_box_specular"};  // the specular pass (an engine
                                                                   // extension: no truth)

TEST(RoomEdits, EveryBundledEditIsCovered) {
    std::set<std::string> listed(kLightsOnly.begin(), kLightsOnly.end());
    listed.insert(kLater.begin(), kLater.end());
    for (const auto& entry : fs::directory_iterator(kRoom / "edits")) {
        if (entry.path().extension() != ".json") continue;
        EXPECT_TRUE(listed.count(entry.path().stem().string())) << entry.path();
    }
}

TEST(RoomEdits, LightsOnlyEditsLoadAndAreAccepted) {
    for (const std::string& name : kLightsOnly) {
        SCOPED_TRACE(name);
        const EditFile edit = loadRoomEdit(name);
        EXPECT_FALSE(!edit.addLights.empty() || !edit.addObjects.empty() ||
                     !edit.removeObjects.empty());
    }
}

TEST(RoomEdits, VirtualEditsAndRemovalsLoad) {
    for (const std::string& name : kLater) {
        SCOPED_TRACE(name);
        const EditFile edit = loadRoomEdit(name);
        EXPECT_TRUE(!edit.addLights.empty() || !edit.addObjects.empty() ||
                    !edit.removeObjects.empty());
    }
    EXPECT_EQ(loadRoomEdit("remove_table").removeObjects, std::vector<std::string>{"table"});
    const EditFile specular = loadRoomEdit("virtual_box_specular");
    ASSERT_TRUE(specular.addObjects.at(0).specular);
    EXPECT_EQ(specular.addObjects[0].specular->shininess, 30.0);
    EXPECT_FALSE(loadRoomEdit("virtual_box").addObjects.at(0).specular);
}

TEST(RoomEdits, LeftOffRightDouble) {
    // The file: {"A": {"scale": 0.0}, "B": {"scale": 2.0}}; C and D are not named.
    const SceneFile& sf = room();
    const EditFile edit = loadRoomEdit("left_off_right_double");
    ASSERT_EQ(edit.lights.size(), 2u);
    const std::vector<Rgb>& nominal = sf.nominalRadiance;
    const std::vector<Rgb> out = editedRadiance(sf, edit, nominal);
    ASSERT_EQ(out.size(), 4u);
    const size_t a = lightIndex(sf, "A"), b = lightIndex(sf, "B");
    EXPECT_EQ(out[a], Rgb{});
    EXPECT_EQ(out[b], nominal[b] * 2.0);
    EXPECT_NE(out[b], Rgb{});
    // All four lights are on in the room's photo, so C and D keep their nominal radiance.
    for (const char* name : {"C", "D"})
        EXPECT_EQ(out[lightIndex(sf, name)], nominal[lightIndex(sf, name)]);
}

TEST(RoomEdits, ColoursSetsTheRadianceInTheFile) {
    const SceneFile& sf = room();
    const std::vector<Rgb> out = editedRadiance(sf, loadRoomEdit("colours"), sf.nominalRadiance);
    EXPECT_EQ(out[lightIndex(sf, "A")], Rgb(14.0, 3.0, 2.0));
    EXPECT_EQ(out[lightIndex(sf, "B")], Rgb(2.5, 12.0, 3.0));
    EXPECT_EQ(out[lightIndex(sf, "C")], Rgb(2.0, 4.0, 15.0));
    EXPECT_EQ(out[lightIndex(sf, "D")], Rgb(12.0, 10.0, 1.5));
}

TEST(RoomEdits, IdentityGivesThePhotosState) {
    const SceneFile& sf = room();
    const EditFile edit = loadRoomEdit("identity");
    EXPECT_TRUE(edit.lights.empty());
    EXPECT_EQ(editedRadiance(sf, edit, sf.nominalRadiance), sf.nominalRadiance);
}

TEST(RoomEdits, ScaleAppliesToTheGivenNominalRadiance) {
    // Where scene.json says "estimate", the caller passes the estimated radiance.
    const SceneFile& sf = room();
    const std::vector<Rgb> estimated(sf.scene.lights.size(), Rgb(1.0, 2.0, 4.0));
    const std::vector<Rgb> out =
        editedRadiance(sf, loadRoomEdit("right_off_left_double"), estimated);
    EXPECT_EQ(out[lightIndex(sf, "A")], Rgb(2.0, 4.0, 8.0));
    EXPECT_EQ(out[lightIndex(sf, "B")], Rgb{});
    EXPECT_EQ(out[lightIndex(sf, "C")], Rgb(1.0, 2.0, 4.0));
}

TEST(RoomEdits, WrongNumberOfNominalRadiancesIsAProgrammingError) {
    const SceneFile& sf = room();
    EXPECT_THROW(editedRadiance(sf, loadRoomEdit("identity"), {Rgb{}}), std::invalid_argument);
}

// ---- a small scene in memory: lights on and off in the photo ---------------------------

/// Lights L1 (on in the photo) and L2 (off); only their names and the photo matter here.
SceneFile twoLightScene() {
    SceneFile sf;
    for (const char* name : {"L1", "L2"}) {
        radiosity::Light light;
        light.name = name;
        sf.scene.lights.push_back(light);
    }
    sf.nominalRadiance = {Rgb(1, 2, 3), Rgb(4, 5, 6)};
    sf.estimateRadiance = {false, false};
    relight::PhotoSpec photo;
    photo.lightsOn = {"L1"};
    sf.photos.push_back(photo);
    return sf;
}

/// loadEdit()'s tests (and editedRadiance()'s on what it loads): twoLightScene(), the edit
/// written to a temporary folder.
class LoadEdit : public ::testing::Test {
  protected:
    TempDir dir;
    SceneFile sf = twoLightScene();

    std::string editFile() const { return (dir.path() / "edit.json").string(); }
    EditFile load(const std::string& text) const {
        return loadEdit(dir.write("edit.json", text), sf);
    }
    /// Loads and returns the InputError's message; fails the test when there is none.
    std::string loadError(const std::string& text) const {
        return errorOf([&] { load(text); });
    }
    /// {"format": "relight-edit/1", "lights": {"L1": entry}}
    static std::string withL1(const json& entry) {
        return json{{"format", "relight-edit/1"}, {"lights", {{"L1", entry}}}}.dump(1);
    }
};

TEST_F(LoadEdit, EmptyEditGivesThePhotosState) {
    const EditFile edit = load(R"({"format":"relight-edit/1"})");
    EXPECT_EQ(edit.file, dir.path() / "edit.json");
    EXPECT_TRUE(edit.lights.empty());
    const std::vector<Rgb> out = editedRadiance(sf, edit, sf.nominalRadiance);
    EXPECT_EQ(out, (std::vector<Rgb>{Rgb(1, 2, 3), Rgb{}}));
}

TEST_F(LoadEdit, LightOffInThePhotoStaysOffUnlessNamed) {
    // Naming only L1 leaves L2 off...
    EditFile edit = load(withL1({{"scale", 0.5}}));
    EXPECT_EQ(editedRadiance(sf, edit, sf.nominalRadiance),
              (std::vector<Rgb>{Rgb(0.5, 1, 1.5), Rgb{}}));
    // ...and scale 1 turns L2 on at its nominal radiance.
    edit = load(R"({"format":"relight-edit/1","lights":{"L2":{"scale":1}}})");
    EXPECT_EQ(editedRadiance(sf, edit, sf.nominalRadiance),
              (std::vector<Rgb>{Rgb(1, 2, 3), Rgb(4, 5, 6)}));
    edit = load(R"({"format":"relight-edit/1","lights":{"L2":{"radiance":[7,8,9]}}})");
    EXPECT_EQ(editedRadiance(sf, edit, sf.nominalRadiance)[1], Rgb(7, 8, 9));
}

TEST_F(LoadEdit, WithoutAPhotoEveryLightIsOn) {
    sf.photos.clear();
    const EditFile edit = load(R"({"format":"relight-edit/1"})");
    EXPECT_EQ(editedRadiance(sf, edit, sf.nominalRadiance), sf.nominalRadiance);
}

TEST_F(LoadEdit, EmptyAddAndRemoveListsChangeNothing) {
    const EditFile edit = load(
        R"({"format":"relight-edit/1","lights":{},"add_lights":[],"add_objects":[],"remove_objects":[]})");
    EXPECT_FALSE(!edit.addLights.empty() || !edit.addObjects.empty() ||
                 !edit.removeObjects.empty());
}

TEST_F(LoadEdit, EditLoadedAgainstAnotherSceneIsAProgrammingError) {
    const EditFile edit = load(withL1({{"scale", 1}}));
    SceneFile other = sf;
    other.scene.lights[0].name = "X";
    EXPECT_THROW(editedRadiance(other, edit, other.nominalRadiance), std::invalid_argument);
}

TEST(RoomEdits, ParseEditReadsTheTextAsLoadEditReadsTheFile) {
    const fs::path file = kRoom / "edits" / "virtual_light_and_box.json";
    std::ifstream in(file);
    const EditFile fromText = relight::parseEdit(in, file, room());
    const EditFile fromFile = loadEdit(file, room());
    EXPECT_EQ(fromText.file, fromFile.file);
    ASSERT_EQ(fromText.addLights.size(), 1u);
    EXPECT_EQ(fromText.addLights[0].corners, fromFile.addLights[0].corners);
    ASSERT_EQ(fromText.addObjects.size(), 1u);
    // The object's file is resolved against the named edit file's folder.
    EXPECT_EQ(fromText.addObjects[0].file, fromFile.addObjects[0].file);
    EXPECT_EQ(fromText.addObjects[0].polygons.size(), fromFile.addObjects[0].polygons.size());

    std::istringstream bad(R"({"format": "relight-edit/1", "lights": {"Q": {"scale": 1}}})");
    const std::string msg = errorOf([&] { relight::parseEdit(bad, file, room()); });
    EXPECT_TRUE(contains(msg, file.string() + ": key \"lights.Q\": unknown light")) << msg;
}

// ---- one bad input per error class -----------------------------------------------------

TEST_F(LoadEdit, MissingFile) {
    const std::string msg = errorOf([&] { loadEdit(dir.path() / "none.json", sf); });
    EXPECT_TRUE(contains(msg, (dir.path() / "none.json").string() + ": file not found")) << msg;
}

TEST_F(LoadEdit, InvalidJsonNamesFileAndLine) {
    const std::string msg = loadError("{\n \"format\": \"relight-edit/1\",\n \"lights\": {,}\n}\n");
    EXPECT_TRUE(contains(msg, editFile() + ": invalid JSON")) << msg;
    EXPECT_TRUE(contains(msg, "line 3")) << msg;
}

TEST_F(LoadEdit, DuplicateKeysAreErrors) {
    std::string msg =
        loadError(R"({"format":"relight-edit/1","lights":{"L1":{"scale":0},"L1":{"scale":2}}})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1\": duplicate key")) << msg;
    msg = loadError(R"({"format":"relight-edit/1","lights":{"L1":{"scale":0,"scale":2}}})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1.scale\": duplicate key")) << msg;
}

TEST_F(LoadEdit, TopLevelMustBeAnObject) {
    const std::string msg = loadError("[1, 2]");
    EXPECT_TRUE(contains(msg, editFile() + ": the top level must be a JSON object")) << msg;
}

TEST_F(LoadEdit, MissingFormat) {
    const std::string msg = loadError(R"({"lights":{}})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"format\": missing required key")) << msg;
}

TEST_F(LoadEdit, WrongFormatIsCheckedFirst) {
    // A scene.json given as an edit: named by its format, not by its unknown keys.
    const std::string msg = loadError(R"({"format":"relight-scene/1","camera":{}})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"format\": expected \"relight-edit/1\", got "
                                           "\"relight-scene/1\""))
        << msg;
    EXPECT_TRUE(contains(loadError(R"({"format":1})"), "key \"format\": expected"));
}

TEST_F(LoadEdit, UnknownTopLevelKey) {
    const std::string msg = loadError(R"({"format":"relight-edit/1","light":{}})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"light\": unknown key")) << msg;
}

TEST_F(LoadEdit, LightsMustBeAnObject) {
    const std::string msg = loadError(R"({"format":"relight-edit/1","lights":[{"L1":{}}]})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights\": expected an object of light names"))
        << msg;
}

TEST_F(LoadEdit, UnknownLightListsTheScenesLights) {
    const std::string msg = loadError(R"({"format":"relight-edit/1","lights":{"Q":{"scale":0}}})");
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.Q\": unknown light \"Q\" (the scene "
                                           "has L1, L2)"))
        << msg;
}

TEST_F(LoadEdit, LightEntryMustBeAnObject) {
    const std::string msg = loadError(withL1(0.5));
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1\": expected an object")) << msg;
}

TEST_F(LoadEdit, LightEntryUnknownKey) {
    const std::string msg = loadError(withL1({{"scale", 1}, {"gain", 2}}));
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1.gain\": unknown key")) << msg;
}

TEST_F(LoadEdit, LightEntryWithBothScaleAndRadiance) {
    const std::string msg = loadError(withL1({{"scale", 1}, {"radiance", {1, 1, 1}}}));
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1\": has both \"scale\" and "
                                           "\"radiance\""))
        << msg;
}

TEST_F(LoadEdit, LightEntryWithNeitherScaleNorRadiance) {
    const std::string msg = loadError(withL1(json::object()));
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1\": says nothing")) << msg;
}

TEST_F(LoadEdit, ScaleMustBeAFiniteNonNegativeNumber) {
    const std::pair<std::string, std::string> cases[] = {
        {R"("2")", "expected a number, got string"},
        {"null", "expected a number, got null"},
        {"-0.5", "scale must not be negative"},
    };
    for (const auto& [value, expected] : cases) {
        const std::string msg =
            loadError(R"({"format":"relight-edit/1","lights":{"L1":{"scale":)" + value + "}}}");
        EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1.scale\": " + expected)) << msg;
    }
}

TEST_F(LoadEdit, OverflowingNumberIsRejected) {
    // nlohmann::json refuses a literal that overflows a double at parse time, so the key
    // path is not known; the reader's "number is not finite" check stays as a safety net.
    for (const char* entry : {R"({"scale":1e999})", R"({"radiance":[1, 2, 1e999]})"}) {
        const std::string msg =
            loadError(R"({"format":"relight-edit/1","lights":{"L1":)" + std::string(entry) + "}}");
        EXPECT_TRUE(contains(msg, editFile() + ": invalid JSON: number overflow")) << msg;
    }
}

TEST_F(LoadEdit, ScaleThatOverflowsTheRadianceIsRefused) {
    // Finite in the file, but 1e308 x L1's nominal 3 overflows a double: refused at load
    // (against scene.json's radiance), naming the key, rather than rendered as inf and NaN.
    const std::string msg = loadError(withL1({{"scale", 1e308}}));
    EXPECT_TRUE(contains(msg, editFile() + ": key \"lights.L1.scale\": the relit image is not "
                                           "finite: the light's radiance overflows (1e+308 x "))
        << msg;
    // The largest scale that does not overflow any channel is accepted.
    const double largest = std::numeric_limits<double>::max() / 4;
    EXPECT_NO_THROW(load(withL1({{"scale", largest}})));
    // A scale applied later to an estimated radiance (nominal 0 at load) is checked then.
    const EditFile edit = load(withL1({{"scale", 1e300}}));
    const std::string later = errorOf([&] {
        editedRadiance(sf, edit, {Rgb(1e10, 1, 1), Rgb(4, 5, 6)});
    });
    EXPECT_TRUE(contains(later, editFile() + ": key \"lights.L1.scale\"")) << later;
}

TEST_F(LoadEdit, RadianceMustBeThreeFiniteNonNegativeNumbers) {
    const std::pair<std::string, std::string> cases[] = {
        {"5", "\"lights.L1.radiance\": expected an array"},
        {"[1, 2]", "\"lights.L1.radiance\": expected an array of 3 elements, got 2"},
        {"[1, 2, 3, 4]", "\"lights.L1.radiance\": expected an array of 3 elements, got 4"},
        {R"([1, "2", 3])", "\"lights.L1.radiance[1]\": expected a number"},
        {"[1, -2, 3]", "\"lights.L1.radiance[1]\": radiance must not be negative"},
    };
    for (const auto& [value, expected] : cases) {
        const std::string msg =
            loadError(R"({"format":"relight-edit/1","lights":{"L1":{"radiance":)" + value + "}}}");
        EXPECT_TRUE(contains(msg, editFile() + ": key " + expected)) << msg;
    }
}

TEST_F(LoadEdit, AddAndRemovePartsMustBeArrays) {
    for (const char* key : {"add_lights", "add_objects", "remove_objects"}) {
        json j = {{"format", "relight-edit/1"}, {key, {{"name", "table"}}}};
        const std::string msg = loadError(j.dump(1));
        EXPECT_TRUE(contains(
            msg, editFile() + ": key \"" + std::string(key) + "\": expected an array, got object"))
            << msg;
    }
}

// ---- virtual lights, virtual objects, removals --------------------------------------------

/// {"format": "relight-edit/1", key: [entry]}
std::string withList(const char* key, const json& entry) {
    return json{{"format", "relight-edit/1"}, {key, json::array({entry})}}.dump(1);
}

json quadLight(const std::string& name) {
    return {{"name", name},
            {"type", "quad"},
            {"vertices", {{0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}}},
            {"radiance", {1, 2, 3}}};
}

TEST_F(LoadEdit, VirtualLightIsRead) {
    const EditFile edit = load(withList("add_lights", quadLight("V1")));
    ASSERT_EQ(edit.addLights.size(), 1u);
    EXPECT_EQ(edit.addLights[0].name, "V1");
    EXPECT_EQ(edit.addLights[0].corners.size(), 4u);
    EXPECT_EQ(edit.addLights[0].radiance, Rgb(1, 2, 3));
}

TEST_F(LoadEdit, VirtualLightErrorsNameTheKey) {
    json zeroArea = quadLight("V1");
    zeroArea["vertices"] = {{0, 0, 2}, {1, 0, 2}, {2, 0, 2}, {3, 0, 2}};
    EXPECT_TRUE(
        contains(loadError(withList("add_lights", zeroArea)),
                 "key \"add_lights[0].vertices\": a light must be a planar convex polygon"));
    json estimate = quadLight("V1");
    estimate["radiance"] = "estimate";
    EXPECT_TRUE(
        contains(loadError(withList("add_lights", estimate)),
                 "key \"add_lights[0].radiance\": a virtual light's radiance must be given"));
    // The format's other types are read with their own fields (a sun has no "radiance").
    const json sun = {
        {"name", "V2"}, {"type", "sun"}, {"direction", {0, 0, 1}}, {"radiance", {1, 1, 1}}};
    EXPECT_TRUE(contains(loadError(withList("add_lights", sun)),
                         "key \"add_lights[0].radiance\": unknown key"));
    json negative = quadLight("V1");
    negative["radiance"] = {1, -1, 1};
    EXPECT_TRUE(contains(loadError(withList("add_lights", negative)),
                         "key \"add_lights[0].radiance[1]\": radiance must not be negative"));
    EXPECT_TRUE(contains(loadError(withList("add_lights", quadLight("L1"))),
                         "key \"add_lights[0].name\": the scene already has a light \"L1\""));
    const json twice = {{"format", "relight-edit/1"},
                        {"add_lights", json::array({quadLight("V"), quadLight("V")})}};
    EXPECT_TRUE(contains(loadError(twice.dump()),
                         "key \"add_lights[1].name\": duplicate light name \"V\""));
    json extra = quadLight("V1");
    extra["colour"] = 1;
    EXPECT_TRUE(contains(loadError(withList("add_lights", extra)), "colour")) << "unknown key";
}

/// A unit cube's six faces as OBJ text (counter-clockwise seen from outside).
const char* kCube = R"(o cube
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
)";

json boxObject(const json& transform) {
    return {{"name", "box"},
            {"file", "cube.obj"},
            {"reflectance", {0.7, 0.2, 0.2}},
            {"transform", transform}};
}

const json kIdentity = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};

TEST_F(LoadEdit, VirtualObjectIsReadRelativeToTheEditAndPlacedByItsTransform) {
    dir.write("cube.obj", kCube);
    // Scale 2 on x, then move by (1, 2, 3): the cube spans [1, 3] x [2, 3] x [3, 4].
    const json t = {{2, 0, 0, 1}, {0, 1, 0, 2}, {0, 0, 1, 3}, {0, 0, 0, 1}};
    const EditFile edit = load(withList("add_objects", boxObject(t)));
    ASSERT_EQ(edit.addObjects.size(), 1u);
    const relight::VirtualObject& box = edit.addObjects[0];
    EXPECT_EQ(box.file, dir.path() / "cube.obj");
    ASSERT_EQ(box.polygons.size(), 6u);
    double area = 0;
    radiosity::Vec3 lo(1e9), hi(-1e9);
    for (const auto& p : box.polygons) {
        area += p.area;
        EXPECT_EQ(p.rho, Rgb(0.7, 0.2, 0.2));
        for (int i = 0; i < p.vertexCount; ++i) {
            lo = glm::min(lo, p.v[i]);
            hi = glm::max(hi, p.v[i]);
        }
        // Outward normals: the face's centre minus the box's centre points along it.
        EXPECT_GT(glm::dot(p.normal, p.centroid() - radiosity::Vec3(2, 2.5, 3.5)), 0);
    }
    EXPECT_NEAR(area, 2 * (2 * 1 + 2 * 1 + 1 * 1), 1e-12);  // 2 (xy + xz + yz)
    EXPECT_EQ(lo, radiosity::Vec3(1, 2, 3));
    EXPECT_EQ(hi, radiosity::Vec3(3, 3, 4));
}

TEST_F(LoadEdit, MirroringTransformKeepsTheFacesOutward) {
    dir.write("cube.obj", kCube);
    const json mirror = {{-1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    const EditFile edit = load(withList("add_objects", boxObject(mirror)));
    ASSERT_EQ(edit.addObjects[0].polygons.size(), 6u);
    for (const auto& p : edit.addObjects[0].polygons)
        EXPECT_GT(glm::dot(p.normal, p.centroid() - radiosity::Vec3(-0.5, 0.5, 0.5)), 0);
}

TEST_F(LoadEdit, VirtualObjectErrorsNameTheKey) {
    EXPECT_TRUE(contains(loadError(withList("add_objects", boxObject(kIdentity))),
                         "key \"add_objects[0].file\": geometry file \"" +
                             (dir.path() / "cube.obj").string() + "\" not found"));
    dir.write("cube.obj", kCube);
    json bright = boxObject(kIdentity);
    bright["reflectance"] = {0.5, 1.0, 0.5};
    EXPECT_TRUE(contains(loadError(withList("add_objects", bright)),
                         "key \"add_objects[0].reflectance[1]\": reflectance must be in [0, 1)"));
    const json flat = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 1}};
    EXPECT_TRUE(contains(loadError(withList("add_objects", boxObject(flat))),
                         "key \"add_objects[0].transform\": the transform is singular"));
    const json projective = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 1, 1}};
    EXPECT_TRUE(contains(loadError(withList("add_objects", boxObject(projective))),
                         "key \"add_objects[0].transform[3][2]\": the last row must be"));
    json nan = boxObject(kIdentity);
    nan["transform"][0][3] = "x";
    EXPECT_TRUE(contains(loadError(withList("add_objects", nan)), "add_objects[0].transform"));
    dir.write("empty.obj", "o nothing\nv 0 0 0\n");
    json empty = boxObject(kIdentity);
    empty["file"] = "empty.obj";
    EXPECT_TRUE(contains(loadError(withList("add_objects", empty)), "has no usable face"));
}

TEST_F(LoadEdit, RemovalsMustNameRemovableObjects) {
    sf.scene.objects = {"table", "wall", "light:L1"};
    sf.objectSettings["table"].removable = true;
    EXPECT_EQ(load(withList("remove_objects", "table")).removeObjects,
              std::vector<std::string>{"table"});
    EXPECT_TRUE(contains(loadError(withList("remove_objects", "chair")),
                         "key \"remove_objects[0]\": the scene has no object \"chair\""));
    EXPECT_TRUE(contains(loadError(withList("remove_objects", "wall")),
                         "object \"wall\" is not marked \"removable\""));
    EXPECT_TRUE(contains(loadError(withList("remove_objects", "light:L1")), "no object"));
}

}  // namespace
