// Tests of edit saving (relight/io/edit_writer.h): every bundled edit of data/room saved into
// another folder loads back as the same edit (exact equalities: saving only copies numbers,
// and the object files must be found again from the new folder), awkward doubles, object
// paths relative to the edit's folder (through a symbolic link too), the unit box against
// the room's 0.3 m box, and failed writes that leave nothing behind and nothing corrupted.
#include "relight/io/edit_writer.h"
#include "temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using radiosity::Rgb;
using radiosity::Vec3;
using relight::EditFile;
using relight::editJson;
using relight::loadEdit;
using relight::SceneFile;
using relight::writeEdit;
using relight::writeUnitBoxObj;
using relight::test::TempDir;

const fs::path kRoom = fs::path(RELIGHT_DATA_DIR) / "room";

const SceneFile& room() {
    static const SceneFile sf = relight::loadScene(kRoom);
    return sf;
}

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

json readJson(const fs::path& file) {
    return json::parse(readText(file));
}

/// The names in `dir`, to check that a failed write left nothing (no temporary file).
std::vector<std::string> listing(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// The message of the `E` that `f` throws; fails the test when it throws none.
template <class E, class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    ADD_FAILURE() << "nothing thrown";
    return {};
}

/// Every field loadEdit fills, compared exactly (the polygons too unless `polygons` is false,
/// for an edit made in memory: the same OBJ file and the same transform give the same faces
/// bit for bit). Object files by fs::equivalent: the saved edit names them from elsewhere.
void expectSameEdit(const EditFile& a, const EditFile& b, bool polygons = true) {
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (const auto& [name, la] : a.lights) {
        SCOPED_TRACE("light " + name);
        ASSERT_EQ(b.lights.count(name), 1u);
        const relight::LightEdit& lb = b.lights.at(name);
        ASSERT_EQ(la.scale.has_value(), lb.scale.has_value());
        ASSERT_EQ(la.radiance.has_value(), lb.radiance.has_value());
        if (la.scale) {
            EXPECT_EQ(*la.scale, *lb.scale);
            EXPECT_EQ(std::signbit(*la.scale), std::signbit(*lb.scale));
        }
        if (la.radiance) {
            EXPECT_EQ(*la.radiance, *lb.radiance);
        }
    }

    ASSERT_EQ(a.addLights.size(), b.addLights.size());
    for (size_t i = 0; i < a.addLights.size(); ++i) {
        SCOPED_TRACE("virtual light " + a.addLights[i].name);
        EXPECT_EQ(a.addLights[i].name, b.addLights[i].name);
        EXPECT_EQ(a.addLights[i].corners, b.addLights[i].corners);
        EXPECT_EQ(a.addLights[i].radiance, b.addLights[i].radiance);
    }

    ASSERT_EQ(a.addObjects.size(), b.addObjects.size());
    for (size_t i = 0; i < a.addObjects.size(); ++i) {
        const relight::VirtualObject& oa = a.addObjects[i];
        const relight::VirtualObject& ob = b.addObjects[i];
        SCOPED_TRACE("virtual object " + oa.name);
        EXPECT_EQ(oa.name, ob.name);
        EXPECT_TRUE(fs::equivalent(oa.file, ob.file)) << oa.file << " vs " << ob.file;
        EXPECT_EQ(oa.reflectance, ob.reflectance);
        EXPECT_EQ(oa.transform, ob.transform);
        ASSERT_EQ(oa.specular.has_value(), ob.specular.has_value());
        if (oa.specular) {
            EXPECT_EQ(oa.specular->ks, ob.specular->ks);
            EXPECT_EQ(oa.specular->shininess, ob.specular->shininess);
        }
        if (!polygons) continue;
        ASSERT_EQ(oa.polygons.size(), ob.polygons.size());
        for (size_t p = 0; p < oa.polygons.size(); ++p) {
            const radiosity::Polygon& pa = oa.polygons[p];
            const radiosity::Polygon& pb = ob.polygons[p];
            EXPECT_EQ(pa.vertexCount, pb.vertexCount);
            EXPECT_EQ(pa.v, pb.v);
            EXPECT_EQ(pa.normal, pb.normal);
            EXPECT_EQ(pa.area, pb.area);
            EXPECT_EQ(pa.rho, pb.rho);
            EXPECT_EQ(pa.object, pb.object);
            EXPECT_EQ(pa.light, pb.light);
        }
    }
    EXPECT_EQ(a.removeObjects, b.removeObjects);
}

// ---- round trips ---------------------------------------------------------------------------

TEST(EditWriter, RoomEditsRoundTripThroughAnotherFolder) {
    TempDir dir("relight_edit_writer");
    // Two levels below the temporary folder: the relative object paths must be recomputed
    // (the bundled "../objects/box.obj" would name a file that is not there).
    const fs::path saved = dir.path() / "saved" / "deeper";
    fs::create_directories(saved);
    size_t edits = 0, objects = 0;
    for (const auto& entry : fs::directory_iterator(kRoom / "edits")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().filename().string());
        ++edits;
        const EditFile original = loadEdit(entry.path(), room());
        const fs::path copy = saved / entry.path().filename();
        writeEdit(copy, original);
        const EditFile reloaded = loadEdit(copy, room());
        expectSameEdit(original, reloaded);

        const json written = readJson(copy);
        EXPECT_EQ(written.at("format"), "relight-edit/1");
        for (const json& o : written.value("add_objects", json::array())) {
            ++objects;
            const std::string file = o.at("file").get<std::string>();
            EXPECT_FALSE(fs::path(file).is_absolute()) << file;
            EXPECT_NE(file, "../objects/box.obj");
            EXPECT_FALSE(contains(file, "\\")) << file;
        }
        // Saving the reloaded edit again gives the same document: nothing drifts.
        EXPECT_EQ(editJson(reloaded, saved), written);
    }
    EXPECT_EQ(edits, 12u);  // every bundled edit, not a vacuous loop
    EXPECT_EQ(objects, 4u);
}

TEST(EditWriter, RoomEditsSavedInTheirOwnFolderAreTheBundledFiles) {
    // The same keys and values as the hand-written files, "../objects/box.obj" included; the
    // only addition is the virtual lights' optional "type": "quad" where a file leaves it out.
    for (const auto& entry : fs::directory_iterator(kRoom / "edits")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().filename().string());
        json expected = readJson(entry.path());
        if (expected.contains("add_lights"))
            for (json& l : expected["add_lights"])
                if (!l.contains("type")) l["type"] = "quad";
        EXPECT_EQ(editJson(loadEdit(entry.path(), room()), entry.path().parent_path()), expected);
    }
}

TEST(EditWriter, AwkwardDoublesSurviveExactly) {
    TempDir dir("relight_edit_writer");
    const double third = 1.0 / 3.0, c = std::cos(0.7), s = std::sin(0.7);
    EditFile edit;
    edit.lights["A"].scale = third;
    edit.lights["B"].radiance = Rgb(0.1 + 0.2, 1e-300, std::numeric_limits<double>::denorm_min());
    edit.lights["C"].scale = -0.0;
    edit.lights["D"].radiance = Rgb(std::numeric_limits<double>::max(), 2.0 / 7.0, 1e22);
    const double x0 = 1.8 + third, y0 = 1.9 - 1.0 / 7.0, z = 2.595 - 1e-9, side = 0.35 / 3.0;
    edit.addLights.push_back(
        {"V",
         {{x0, y0, z}, {x0 + side, y0, z}, {x0 + side, y0 - side, z}, {x0, y0 - side, z}},
         Rgb(16.0 / 3.0, 15.0 / 7.0, 13.0 / 11.0)});
    relight::VirtualObject box;
    box.name = "box";
    box.file = kRoom / "objects" / "box.obj";
    box.reflectance = Rgb(0.7, 0.2 / 3.0, 0.1 + 0.2);
    box.transform = {{{c, -s, 0, 1.25 + third},
                      {s * 1.1, c * 1.1, 0, 1.95 - 1e-17},
                      {0, 0, 1.0 / 3.0, 1e-310},
                      {0, 0, 0, 1}}};
    edit.addObjects.push_back(box);
    writeEdit(dir.path() / "edit.json", edit);
    const EditFile reloaded = loadEdit(dir.path() / "edit.json", room());
    expectSameEdit(edit, reloaded, /*polygons=*/false);  // made in memory: no polygons
    ASSERT_EQ(reloaded.lights.count("C"), 1u);
    EXPECT_TRUE(std::signbit(*reloaded.lights.at("C").scale));  // -0.0 stays -0.0
    ASSERT_EQ(reloaded.addObjects.size(), 1u);
    EXPECT_EQ(reloaded.addObjects[0].polygons.size(), 6u);
    // Saved and loaded once more: the same faces, bit for bit.
    writeEdit(dir.path() / "again.json", reloaded);
    expectSameEdit(reloaded, loadEdit(dir.path() / "again.json", room()));
}

// ---- object paths ----------------------------------------------------------------------------

TEST(EditWriter, ObjectPathsAreRelativeToTheEditFolder) {
    TempDir dir("relight_edit_writer");
    const fs::path scene = dir.path() / "scene";
    fs::create_directories(scene / "objects");
    fs::create_directories(scene / "edits" / "a");
    writeUnitBoxObj(scene / "objects" / "box.obj");

    EditFile edit;
    edit.addObjects.push_back({"box", scene / "objects" / "box.obj", Rgb(0.5, 0.5, 0.5), {}, {}});
    const auto fileFrom = [&](const fs::path& folder) {
        return editJson(edit, folder).at("add_objects").at(0).at("file").get<std::string>();
    };
    EXPECT_EQ(fileFrom(scene / "edits"), "../objects/box.obj");
    EXPECT_EQ(fileFrom(scene / "edits" / "a"), "../../objects/box.obj");
    EXPECT_EQ(fileFrom(scene), "objects/box.obj");
    EXPECT_EQ(fileFrom(scene / "objects"), "box.obj");
    EXPECT_EQ(fileFrom(scene / "edits" / "a" / ".."), "../objects/box.obj");
    // As loadEdit stores it: the edit's folder joined with the name in the file.
    edit.addObjects[0].file = scene / "edits" / "a" / ".." / ".." / "objects" / "box.obj";
    EXPECT_EQ(fileFrom(scene / "edits"), "../objects/box.obj");
}

TEST(EditWriter, ObjectPathsFollowSymlinkedFolders) {
    // edits/ reached through a link elsewhere: the OS resolves the link before the "..", so
    // the name must be computed from the real folder ("../objects/box.obj"), not from the
    // link's lexical place ("../real/objects/box.obj", which loadEdit would not find).
    TempDir dir("relight_edit_writer");
    const fs::path real = dir.path() / "real";
    fs::create_directories(real / "edits");
    fs::create_directories(real / "objects");
    writeUnitBoxObj(real / "objects" / "box.obj");
    std::error_code ec;
    fs::create_directory_symlink(real / "edits", dir.path() / "link", ec);
    if (ec) GTEST_SKIP() << "cannot make a symbolic link: " << ec.message();

    EditFile edit;
    edit.addObjects.push_back({"box",
                               real / "objects" / "box.obj",
                               Rgb(0.5, 0.5, 0.5),
                               {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}},
                               {}});
    const fs::path file = dir.path() / "link" / "edit.json";
    writeEdit(file, edit);
    EXPECT_EQ(readJson(file).at("add_objects").at(0).at("file"), "../objects/box.obj");
    const EditFile reloaded = loadEdit(file, room());
    ASSERT_EQ(reloaded.addObjects.size(), 1u);
    EXPECT_TRUE(fs::equivalent(reloaded.addObjects[0].file, real / "objects" / "box.obj"));
}

TEST(EditWriter, EmptyPartsAreLeftOut) {
    EXPECT_EQ(editJson(EditFile{}, "."), json({{"format", "relight-edit/1"}}));
    EditFile edit;
    edit.removeObjects = {"table"};
    EXPECT_EQ(editJson(edit, "."),
              json({{"format", "relight-edit/1"}, {"remove_objects", {"table"}}}));
}

TEST(EditWriter, EditsTheFileCannotSayAreRefused) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EditFile edit;
    edit.lights["A"].scale = nan;
    EXPECT_TRUE(contains(errorOf<std::invalid_argument>([&] { editJson(edit, "."); }),
                         "key \"lights.A.scale\""));
    edit.lights["A"] = {};
    EXPECT_TRUE(contains(errorOf<std::invalid_argument>([&] { editJson(edit, "."); }),
                         "key \"lights.A\": give exactly one of scale and radiance"));
    edit.lights["A"] = {1.0, Rgb(1, 1, 1)};
    EXPECT_TRUE(contains(errorOf<std::invalid_argument>([&] { editJson(edit, "."); }),
                         "key \"lights.A\": give exactly one"));
    edit.lights.clear();
    edit.addLights.push_back({"V", {{0, 0, 0}, {1, 0, 0}, {0, 1, inf}}, Rgb(1, 1, 1)});
    EXPECT_TRUE(contains(errorOf<std::invalid_argument>([&] { editJson(edit, "."); }),
                         "key \"add_lights[0].vertices[2][2]\""));
    edit.addLights.clear();
    relight::VirtualObject box;
    box.name = "box";
    box.file = kRoom / "objects" / "box.obj";
    box.transform[0][3] = -inf;
    edit.addObjects.push_back(box);
    EXPECT_TRUE(contains(errorOf<std::invalid_argument>([&] { editJson(edit, "."); }),
                         "key \"add_objects[0].transform[0][3]\""));
    edit.addObjects[0].transform[0][3] = 0;
    edit.addObjects[0].file.clear();
    EXPECT_TRUE(contains(errorOf<std::invalid_argument>([&] { editJson(edit, "."); }),
                         "key \"add_objects[0].file\""));
}

// ---- the unit box ----------------------------------------------------------------------------

TEST(EditWriter, UnitBoxScaledBy0_3IsTheRoomsBox) {
    TempDir dir("relight_edit_writer");
    writeUnitBoxObj(dir.path() / "unit_box.obj");
    // Written by hand rather than by writeEdit: this checks the OBJ, not the writer.
    const json identity = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    const json scaled = {{0.3, 0, 0, 0}, {0, 0.3, 0, 0}, {0, 0, 0.3, 0}, {0, 0, 0, 1}};
    const json object = {{"reflectance", {0.5, 0.5, 0.5}}};
    json unit = object, unitScaled = object, roomBox = object;
    unit.update({{"name", "unit"}, {"file", "unit_box.obj"}, {"transform", identity}});
    unitScaled.update({{"name", "scaled"}, {"file", "unit_box.obj"}, {"transform", scaled}});
    roomBox.update({{"name", "room_box"},
                    {"file", (kRoom / "objects" / "box.obj").string()},
                    {"transform", identity}});
    const fs::path file = dir.write(
        "edit.json",
        json{{"format", "relight-edit/1"}, {"add_objects", {unit, unitScaled, roomBox}}}.dump());
    const EditFile edit = loadEdit(file, room());
    EXPECT_TRUE(edit.warnings.empty());
    ASSERT_EQ(edit.addObjects.size(), 3u);
    const auto& unitFaces = edit.addObjects[0].polygons;
    const auto& scaledFaces = edit.addObjects[1].polygons;
    const auto& boxFaces = edit.addObjects[2].polygons;
    ASSERT_EQ(unitFaces.size(), 6u);
    ASSERT_EQ(scaledFaces.size(), 6u);
    ASSERT_EQ(boxFaces.size(), 6u);

    // The unit cube itself: [-0.5, 0.5]^2 x [0, 1], area 6, fronts outward.
    radiosity::Bounds3 bounds;
    double area = 0;
    for (const radiosity::Polygon& p : unitFaces) {
        bounds.extend(p.bounds());
        area += p.area;
        EXPECT_GT(glm::dot(p.normal, p.centroid() - Vec3(0, 0, 0.5)), 0);
    }
    EXPECT_EQ(bounds.lo, Vec3(-0.5, -0.5, 0));
    EXPECT_EQ(bounds.hi, Vec3(0.5, 0.5, 1));
    EXPECT_NEAR(area, 6.0, 1e-12);

    // Scaled by 0.3: the room's box, face for face (same corners and normal), in any order.
    double scaledArea = 0, boxArea = 0;
    for (const radiosity::Polygon& p : boxFaces) boxArea += p.area;
    for (const radiosity::Polygon& p : scaledFaces) {
        scaledArea += p.area;
        EXPECT_GT(glm::dot(p.normal, p.centroid() - Vec3(0, 0, 0.15)), 0);
        int matches = 0;
        for (const radiosity::Polygon& q : boxFaces) {
            if (glm::length(p.normal - q.normal) > 1e-12 || p.vertexCount != q.vertexCount)
                continue;
            bool sameCorners = true;
            for (int i = 0; i < p.vertexCount; ++i) {
                bool found = false;
                for (int k = 0; k < q.vertexCount; ++k)
                    found = found || glm::length(p.v[i] - q.v[k]) < 1e-12;
                sameCorners = sameCorners && found;
            }
            matches += sameCorners ? 1 : 0;
            EXPECT_NEAR(p.area, q.area, 1e-12);
        }
        EXPECT_EQ(matches, 1) << "face with normal " << p.normal.x << " " << p.normal.y << " "
                              << p.normal.z;
    }
    EXPECT_NEAR(scaledArea, 6 * 0.09, 1e-12);
    EXPECT_NEAR(boxArea, 6 * 0.09, 1e-12);
}

// ---- failed writes ---------------------------------------------------------------------------

TEST(EditWriter, MissingFolderThrowsNamingTheFileAndLeavesNothing) {
    TempDir dir("relight_edit_writer");
    EditFile edit;
    edit.lights["A"].scale = 0.5;
    const fs::path file = dir.path() / "missing" / "edit.json";
    const std::string msg = errorOf<std::runtime_error>([&] { writeEdit(file, edit); });
    EXPECT_TRUE(contains(msg, file.string())) << msg;
    const fs::path obj = dir.path() / "missing" / "box.obj";
    const std::string objMsg = errorOf<std::runtime_error>([&] { writeUnitBoxObj(obj); });
    EXPECT_TRUE(contains(objMsg, obj.string())) << objMsg;
    EXPECT_FALSE(fs::exists(dir.path() / "missing"));
    EXPECT_TRUE(listing(dir.path()).empty());
}

TEST(EditWriter, FailedWriteLeavesTheExistingFileAsItWas) {
    TempDir dir("relight_edit_writer");
    const fs::path file = dir.path() / "edit.json";
    EditFile first;
    first.lights["A"].scale = 0.5;
    writeEdit(file, first);
    const std::string before = readText(file);

    // An edit the file cannot say: refused before the file is touched.
    EditFile bad;
    bad.lights["B"].scale = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(writeEdit(file, bad), std::invalid_argument);
    EXPECT_EQ(readText(file), before);
    EXPECT_EQ(listing(dir.path()), std::vector<std::string>{"edit.json"});

    // A write that fails (the temporary file next to it cannot be made; a read-only folder
    // would do, but not for root): the old file stays whole.
    fs::create_directory(dir.path() / ".tmp-edit.json");
    EditFile second;
    second.lights["B"].scale = 2.0;
    const std::string msg = errorOf<std::runtime_error>([&] { writeEdit(file, second); });
    EXPECT_TRUE(contains(msg, file.string())) << msg;
    EXPECT_EQ(readText(file), before);
    fs::remove(dir.path() / ".tmp-edit.json");

    // And a write that works replaces it whole, leaving no temporary file.
    writeEdit(file, second);
    const EditFile reloaded = loadEdit(file, room());
    expectSameEdit(second, reloaded);
    EXPECT_EQ(listing(dir.path()), std::vector<std::string>{"edit.json"});
}

}  // namespace
