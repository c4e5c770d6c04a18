// Tests of scene loading (relight/io/scene_file.h, relight/io/obj_reader.h): the bundled scenes,
// the OBJ reader's forms, the documented repairs, and one bad input per error class, each
// of which must raise an InputError naming the file and the line or key path.
#include "relight/io/scene_file.h"

#include <gtest/gtest.h>

#include "radiosity/emitter.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "relight/io/obj_reader.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using radiosity::Vec3;
using relight::InputError;
using relight::loadScene;
using relight::SceneFile;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

/// The number of warnings that contain `part`.
int countWarnings(const SceneFile& sf, const std::string& part) {
    int n = 0;
    for (const std::string& w : sf.warnings) n += contains(w, part) ? 1 : 0;
    return n;
}

std::string allWarnings(const SceneFile& sf) {
    std::string s;
    for (const std::string& w : sf.warnings) s += w + "\n";
    return s;
}

using relight::test::TempDir;

// A one-face scene: a 1 m x 1 m floor at z = 0 lit by a 0.2 m x 0.2 m light at z = 0.9
// facing down, seen from above by a camera looking down -z.
const char* const kFloorObj =
    "# floor\n"     // line 1
    "o floor\n"     // line 2
    "v 0 0 0\n"     // line 3
    "v 1 0 0\n"     // line 4
    "v 1 1 0\n"     // line 5
    "v 0 1 0\n"     // line 6
    "f 1 2 3 4\n";  // line 7

json baseScene() {
    return json::parse(R"({
      "format": "relight-scene/1",
      "geometry": ["box.obj"],
      "objects": { "floor": { "removable": false } },
      "camera": {
        "width": 64, "height": 48,
        "K": [[50, 0, 31.5], [0, 50, 23.5], [0, 0, 1]],
        "world_to_camera": [[1, 0, 0, -0.5], [0, -1, 0, 0.5], [0, 0, -1, 2]]
      },
      "photos": [ { "file": "photo.exr", "encoding": "linear", "lights_on": ["L"] } ],
      "lights": [
        { "name": "L", "type": "quad",
          "vertices": [[0.4, 0.4, 0.9], [0.4, 0.6, 0.9], [0.6, 0.6, 0.9], [0.6, 0.4, 0.9]],
          "radiance": [1, 2, 3] }
      ]
    })");
}

/// loadScene()'s tests: the bundled scenes, and a scene written to a temporary folder
/// (tests change `scene` and `obj` first).
class LoadScene : public ::testing::Test {
  protected:
    TempDir dir;
    json scene = baseScene();
    std::string obj = kFloorObj;

    std::string jsonFile() const { return (dir.path() / "scene.json").string(); }
    std::string objFile() const { return (dir.path() / "box.obj").string(); }

    void write() const {
        dir.write("scene.json", scene.dump(1));
        dir.write("box.obj", obj);
    }
    SceneFile load() const {
        write();
        return loadScene(dir.path());
    }
    /// Loads and returns the InputError's message; fails the test when there is none.
    std::string loadError() const {
        write();
        try {
            loadScene(dir.path());
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "loadScene() accepted a bad scene";
        return {};
    }
};

// ---- the bundled scenes ----------------------------------------------------------------

TEST_F(LoadScene, RoomCountsAreasAndSettings) {
    const SceneFile sf = loadScene(fs::path(RELIGHT_DATA_DIR) / "room");
    EXPECT_TRUE(sf.warnings.empty()) << allWarnings(sf);
    // 9 OBJ objects (floor, ceiling, 4 walls, poster, table, cabinet) + 4 "light:X".
    ASSERT_EQ(sf.scene.objects.size(), 13u);
    EXPECT_EQ(sf.scene.objects[0], "floor");
    EXPECT_EQ(sf.scene.objects[8], "cabinet");
    EXPECT_EQ(sf.scene.objects[9], "light:A");
    // 6 room faces + poster + table (5 boxes x 6) + cabinet (6) = 43, less the 4 legs' tops
    // inside the table top (radiosity/buried.h), then 4 light quads.
    EXPECT_EQ(sf.buriedPolygons, 4);
    EXPECT_NEAR(sf.buriedArea, 4 * 0.05 * 0.05, 1e-12);
    ASSERT_EQ(sf.scene.polygons.size(), 43u);
    const auto& floor = sf.scene.polygons[0];
    EXPECT_EQ(floor.object, sf.scene.findObject("floor"));
    EXPECT_EQ(floor.vertexCount, 4);
    EXPECT_NEAR(floor.area, 12.0, 1e-12);
    EXPECT_NEAR(floor.normal.z, 1.0, 1e-12);
    // average_reflectance 0.6 where objects gives none; wall_right has its own.
    EXPECT_EQ(floor.rho, radiosity::Rgb::gray(0.6));
    const int wallRight = sf.scene.findObject("wall_right");
    for (const auto& p : sf.scene.polygons)
        if (p.object == wallRight) {
            EXPECT_EQ(p.rho, radiosity::Rgb(0.7, 0.72, 0.62));
        }
    ASSERT_TRUE(sf.averageReflectance.has_value());
    EXPECT_DOUBLE_EQ(*sf.averageReflectance, 0.6);
    EXPECT_TRUE(sf.objectSettings.at("table").removable);
    EXPECT_FALSE(sf.objectSettings.at("wall_front").removable);

    ASSERT_EQ(sf.scene.lights.size(), 4u);
    const char* names[] = {"A", "B", "C", "D"};
    for (int i = 0; i < 4; ++i) {
        const auto& light = sf.scene.lights[static_cast<size_t>(i)];
        EXPECT_EQ(light.name, names[i]);
        ASSERT_EQ(light.polygons.size(), 1u);
        const auto& p = sf.scene.polygons[static_cast<size_t>(light.polygons[0])];
        EXPECT_EQ(light.polygons[0], 39 + i);
        EXPECT_EQ(p.light, i);
        EXPECT_EQ(p.rho, radiosity::Rgb{});
        EXPECT_EQ(sf.scene.objects[static_cast<size_t>(p.object)],
                  std::string("light:") + names[i]);
        EXPECT_NEAR(p.area, 0.09, 1e-12);
        EXPECT_NEAR(p.normal.z, -1.0, 1e-12);  // emits down into the room
        EXPECT_FALSE(sf.estimateRadiance[static_cast<size_t>(i)]);
        EXPECT_EQ(light.radiance, sf.nominalRadiance[static_cast<size_t>(i)]);  // all on
    }
    EXPECT_EQ(sf.nominalRadiance[0], radiosity::Rgb(13.0, 11.2, 9.0));

    ASSERT_EQ(sf.photos.size(), 1u);
    EXPECT_EQ(sf.photos[0].file, fs::path(RELIGHT_DATA_DIR) / "room" / "photo.exr");
    EXPECT_EQ(sf.photos[0].encoding, relight::PhotoSpec::Encoding::linear);
    EXPECT_EQ(sf.photos[0].lightsOn.size(), 4u);
}

TEST_F(LoadScene, ACopyWithoutPolygonsKeepsEverythingElseAndLeavesTheSceneWhole) {
    SceneFile sf = loadScene(fs::path(RELIGHT_DATA_DIR) / "room");
    const size_t polygons = sf.scene.polygons.size();
    ASSERT_GT(polygons, 0u);
    const SceneFile copy = copyWithoutPolygons(sf);
    EXPECT_TRUE(copy.scene.polygons.empty());
    EXPECT_EQ(sf.scene.polygons.size(), polygons);  // the original as it was
    // What render reads after the preparation: the lights, the camera, the names.
    ASSERT_EQ(copy.scene.lights.size(), sf.scene.lights.size());
    for (size_t l = 0; l < sf.scene.lights.size(); ++l) {
        EXPECT_EQ(copy.scene.lights[l].name, sf.scene.lights[l].name);
        EXPECT_EQ(copy.scene.lights[l].polygons, sf.scene.lights[l].polygons);
    }
    EXPECT_EQ(copy.scene.objects, sf.scene.objects);
    EXPECT_EQ(copy.camera.width, sf.camera.width);
    EXPECT_EQ(copy.nominalRadiance.size(), sf.nominalRadiance.size());
    EXPECT_EQ(copy.estimateRadiance, sf.estimateRadiance);
    EXPECT_EQ(copy.dir, sf.dir);
}

TEST_F(LoadScene, ParseSceneReadsTheTextAsLoadSceneReadsTheFile) {
    const fs::path roomDir = fs::path(RELIGHT_DATA_DIR) / "room";
    std::ifstream file(roomDir / "scene.json");
    const SceneFile fromText = relight::parseScene(file, roomDir);
    const SceneFile fromFile = loadScene(roomDir);
    EXPECT_EQ(fromText.dir, fromFile.dir);
    EXPECT_EQ(fromText.scene.objects, fromFile.scene.objects);
    ASSERT_EQ(fromText.scene.polygons.size(), fromFile.scene.polygons.size());
    for (size_t i = 0; i < fromText.scene.polygons.size(); ++i)
        EXPECT_EQ(fromText.scene.polygons[i].v, fromFile.scene.polygons[i].v);
    EXPECT_EQ(fromText.nominalRadiance, fromFile.nominalRadiance);
    EXPECT_EQ(fromText.camera.fx, fromFile.camera.fx);
    EXPECT_EQ(fromText.geometryFiles, fromFile.geometryFiles);
    ASSERT_EQ(fromText.photos.size(), 1u);
    EXPECT_EQ(fromText.photos[0].file, fromFile.photos[0].file);

    // Messages name <dir>/scene.json, as loadScene()'s do.
    std::istringstream bad("{\n \"format\": 1\n}\n");
    try {
        relight::parseScene(bad, roomDir);
        ADD_FAILURE() << "accepted a bad format";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), (roomDir / "scene.json").string() + ": key \"format\""))
            << e.what();
    }
}

TEST_F(LoadScene, RoomCameraMatchesRowMajorWorldToCamera) {
    const fs::path room = fs::path(RELIGHT_DATA_DIR) / "room";
    const SceneFile sf = loadScene(room);
    std::ifstream in(room / "scene.json");
    const json W = json::parse(in)["camera"]["world_to_camera"];
    const relight::Camera& cam = sf.camera;
    EXPECT_EQ(cam.width, 320);
    EXPECT_EQ(cam.height, 240);
    EXPECT_DOUBLE_EQ(cam.fx, 170.0);
    EXPECT_DOUBLE_EQ(cam.cy, 119.5);
    // glm is column-major: cameraFromWorldR[c][r] is R[r][c] (R is not symmetric here).
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            EXPECT_DOUBLE_EQ(cam.cameraFromWorldR[c][r], W[r][c].get<double>()) << r << c;
    // Position -R^T t computed by hand from the rows.
    for (int c = 0; c < 3; ++c) {
        double expected = 0;
        for (int r = 0; r < 3; ++r) expected -= W[r][c].get<double>() * W[r][3].get<double>();
        EXPECT_NEAR(cam.position()[c], expected, 1e-12);
    }
    // A point on the optical axis (third row of R) projects to the principal point.
    const Vec3 axis{W[2][0].get<double>(), W[2][1].get<double>(), W[2][2].get<double>()};
    double u = 0, v = 0, depth = 0;
    ASSERT_TRUE(cam.project(cam.position() + 2.0 * axis, u, v, depth));
    EXPECT_NEAR(u, 159.5, 1e-9);
    EXPECT_NEAR(v, 119.5, 1e-9);
    EXPECT_NEAR(depth, 2.0, 1e-9);
}

TEST_F(LoadScene, CornellCountsAndCamera) {
    const SceneFile sf = loadScene(fs::path(RELIGHT_DATA_DIR) / "cornell");
    EXPECT_TRUE(sf.warnings.empty()) << allWarnings(sf);
    // floor, ceiling, back_wall, left_wall, right_wall, short_block, tall_block + light.
    ASSERT_EQ(sf.scene.objects.size(), 8u);
    EXPECT_EQ(sf.scene.objects[7], "light:light");
    // 1 + 1 + 1 + 2 (left wall is two triangles) + 1 + 5 + 5 faces, then the light.
    ASSERT_EQ(sf.scene.polygons.size(), 17u);
    ASSERT_EQ(sf.scene.lights.size(), 1u);
    const auto& lp = sf.scene.polygons[16];
    EXPECT_EQ(lp.light, 0);
    EXPECT_NEAR(lp.area, 0.13 * 0.105, 1e-12);
    EXPECT_NEAR(lp.normal.y, -1.0, 1e-12);
    EXPECT_EQ(sf.scene.lights[0].radiance, radiosity::Rgb(17, 12, 4));

    const relight::Camera& cam = sf.camera;
    const Vec3 pos = cam.position();
    EXPECT_NEAR(pos.x, 0.278, 1e-12);
    EXPECT_NEAR(pos.y, 0.273, 1e-12);
    EXPECT_NEAR(pos.z, -0.8, 1e-12);
    double u = 0, v = 0, depth = 0;
    // Straight ahead: the centre of the back wall projects to (cx, cy).
    ASSERT_TRUE(cam.project({0.278, 0.273, 0.5592}, u, v, depth));
    EXPECT_NEAR(u, 127.5, 1e-9);
    EXPECT_NEAR(v, 127.5, 1e-9);
    EXPECT_NEAR(depth, 1.3592, 1e-12);
    // Xc = (-0.1, 0, 1): world +x is image left.
    ASSERT_TRUE(cam.project({0.378, 0.273, 0.2}, u, v, depth));
    EXPECT_NEAR(u, 127.5 - 35.84, 1e-9);
    EXPECT_NEAR(v, 127.5, 1e-9);
    // Xc = (0, -0.1, 1): world +y (up) is image up.
    ASSERT_TRUE(cam.project({0.278, 0.373, 0.2}, u, v, depth));
    EXPECT_NEAR(u, 127.5, 1e-9);
    EXPECT_NEAR(v, 127.5 - 35.84, 1e-9);
    // Behind the camera.
    EXPECT_FALSE(cam.project({0.278, 0.273, -1.0}, u, v, depth));
}

TEST_F(LoadScene, SetPhotoLightStateFollowsFirstPhoto) {
    SceneFile sf = loadScene(fs::path(RELIGHT_DATA_DIR) / "room");
    sf.photos[0].lightsOn = {"B", "D"};
    sf.setPhotoLightState();
    EXPECT_EQ(sf.scene.lights[0].radiance, radiosity::Rgb{});
    EXPECT_EQ(sf.scene.lights[1].radiance, sf.nominalRadiance[1]);
    EXPECT_EQ(sf.scene.lights[2].radiance, radiosity::Rgb{});
    EXPECT_EQ(sf.scene.lights[3].radiance, sf.nominalRadiance[3]);
    // Without photos every light is on.
    sf.photos.clear();
    sf.setPhotoLightState();
    for (size_t i = 0; i < 4; ++i) EXPECT_EQ(sf.scene.lights[i].radiance, sf.nominalRadiance[i]);
}

// ---- fixture scenes that load ------------------------------------------------------------

TEST_F(LoadScene, BaseSceneLoads) {
    const SceneFile sf = load();
    EXPECT_TRUE(sf.warnings.empty()) << allWarnings(sf);
    ASSERT_EQ(sf.scene.polygons.size(), 2u);
    EXPECT_EQ(sf.scene.polygons[0].rho, radiosity::Rgb::gray(0.5));  // no hint: 0.5
    EXPECT_EQ(sf.scene.lights[0].radiance, radiosity::Rgb(1, 2, 3));
}

TEST_F(LoadScene, AFloorRunningUnderAWallIsCutAlongItAndTheLightStaysLast) {
    // A wall standing across the 1 m floor at x = 0.3 (facing -x): the floor is cut in two
    // along it (radiosity/contact_split.h), before the light's face is added.
    obj = std::string(kFloorObj) +
          "o wall\nv 0.3 0 0\nv 0.3 0 0.5\nv 0.3 1 0.5\nv 0.3 1 0\nf 5 6 7 8\n";
    const SceneFile sf = load();
    EXPECT_TRUE(sf.warnings.empty()) << allWarnings(sf);
    EXPECT_EQ(sf.contactSplit.polygonsCut, 1);
    EXPECT_EQ(sf.contactSplit.piecesAdded, 1);
    ASSERT_EQ(sf.scene.polygons.size(), 4u);  // floor's pieces, wall, light
    const int floor = sf.scene.findObject("floor");
    EXPECT_EQ(sf.scene.polygons[0].object, floor);
    EXPECT_EQ(sf.scene.polygons[2].object, floor);
    EXPECT_NEAR(sf.scene.polygons[0].area + sf.scene.polygons[2].area, 1.0, 1e-12);
    EXPECT_EQ(sf.scene.lights[0].polygons, std::vector<int>{3});
    EXPECT_EQ(sf.scene.polygons[3].light, 0);
    EXPECT_TRUE(contains(relight::contactSplitLine(sf), "1 polygons cut along 1 lines"))
        << relight::contactSplitLine(sf);
}

/// OBJ text of a box (object `name`, its 8 vertices numbered from first + 1), faces
/// counter-clockwise seen from outside.
std::string objBox(const std::string& name, double x0, double y0, double z0, double x1, double y1,
                   double z1, int first) {
    std::string out = "o " + name + "\n";
    const double xs[2] = {x0, x1}, ys[2] = {y0, y1}, zs[2] = {z0, z1};
    const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                              {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (const auto& c : corner)
        out += "v " + std::to_string(xs[c[0]]) + " " + std::to_string(ys[c[1]]) + " " +
               std::to_string(zs[c[2]]) + "\n";
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {2, 3, 7, 6}, {1, 2, 6, 5}, {3, 0, 4, 7}};
    for (const auto& q : quads)
        out += "f " + std::to_string(first + q[0] + 1) + " " + std::to_string(first + q[1] + 1) +
               " " + std::to_string(first + q[2] + 1) + " " + std::to_string(first + q[3] + 1) +
               "\n";
    return out;
}

TEST_F(LoadScene, FacesInsideSolidsAreLeftOutAndTheLightStaysLast) {
    // A slab box and a wall box standing on it across its width: after the cut, the slab's
    // piece under the wall and the wall's foot lie inside solid matter (radiosity/buried.h).
    // The camera above sees the slab's top on both sides of the wall, not under it.
    obj = objBox("floor", 0, 0, -0.1, 1, 1, 0, 0) + objBox("wall", 0.3, 0, 0, 0.4, 1, 0.5, 8);
    const SceneFile sf = load();
    EXPECT_TRUE(sf.warnings.empty()) << allWarnings(sf);
    EXPECT_EQ(sf.buriedPolygons, 2);
    EXPECT_NEAR(sf.buriedArea, 2 * 0.1, 1e-9);
    // 12 faces, the slab's top cut in 3 (2 pieces added), 2 left out, then the light.
    ASSERT_EQ(sf.scene.polygons.size(), 12u + 2 - 2 + 1);
    EXPECT_EQ(sf.scene.lights[0].polygons, std::vector<int>{12});
    EXPECT_EQ(sf.scene.polygons[12].light, 0);
    EXPECT_TRUE(contains(relight::contactSplitLine(sf), "2 faces inside solids left out"))
        << relight::contactSplitLine(sf);
}

TEST_F(LoadScene, LightsOffInPhotoAreOff) {
    scene["lights"].push_back({{"name", "M"},
                               {"type", "quad"},
                               {"vertices", {{0.1, 0.1, 0.9}, {0.1, 0.2, 0.9}, {0.2, 0.1, 0.9}}},
                               {"radiance", {4, 4, 4}}});
    const SceneFile sf = load();
    ASSERT_EQ(sf.scene.lights.size(), 2u);
    EXPECT_EQ(sf.scene.lights[0].radiance, radiosity::Rgb(1, 2, 3));
    EXPECT_EQ(sf.scene.lights[1].radiance, radiosity::Rgb{});  // not in lights_on
    EXPECT_EQ(sf.nominalRadiance[1], radiosity::Rgb(4, 4, 4));
    EXPECT_EQ(sf.scene.polygons.back().vertexCount, 3);
}

TEST_F(LoadScene, EstimatedRadiance) {
    scene["lights"][0]["radiance"] = "estimate";
    const SceneFile sf = load();
    EXPECT_TRUE(sf.estimateRadiance[0]);
    EXPECT_EQ(sf.nominalRadiance[0], radiosity::Rgb{});
}

TEST_F(LoadScene, LightWithSixVerticesIsAFan) {
    json hexagon = json::array();
    for (int k = 0; k < 6; ++k) {
        // Clockwise seen from above = counter-clockwise seen from below, where it emits.
        const double a = -k * 3.14159265358979 / 3;
        hexagon.push_back({0.5 + 0.1 * std::cos(a), 0.5 + 0.1 * std::sin(a), 0.9});
    }
    scene["lights"][0]["vertices"] = hexagon;
    const SceneFile sf = load();
    const auto& light = sf.scene.lights[0];
    ASSERT_EQ(light.polygons.size(), 4u);
    double area = 0;
    for (int p : light.polygons) {
        const auto& poly = sf.scene.polygons[static_cast<size_t>(p)];
        EXPECT_EQ(poly.vertexCount, 3);
        EXPECT_EQ(poly.light, 0);
        EXPECT_EQ(sf.scene.objects[static_cast<size_t>(poly.object)], "light:L");
        EXPECT_LT(poly.normal.z, -0.999);
        area += poly.area;
    }
    EXPECT_NEAR(area, 1.5 * std::sqrt(3.0) * 0.01, 1e-9);
}

TEST_F(LoadScene, PhotoEncodingInferredFromExtension) {
    scene["photos"][0].erase("encoding");
    scene["photos"][0]["file"] = "shots/photo.PNG";
    const SceneFile sf = load();
    EXPECT_EQ(sf.photos[0].encoding, relight::PhotoSpec::Encoding::srgb);
    EXPECT_EQ(sf.photos[0].file, dir.path() / "shots/photo.PNG");  // not checked for existence
}

TEST_F(LoadScene, ConvexPentagonIsSplitIntoAFanWithWarning) {
    obj += "o pent\nv 0 0 1\nv 1 0 1\nv 1.5 0.5 1\nv 1 1 1\nv 0 1 1\nf 5 6 7 8 9\n";  // f: line 14
    const SceneFile sf = load();
    EXPECT_EQ(countWarnings(sf, objFile() + ":14: convex face with 5 vertices"), 1)
        << allWarnings(sf);
    const int pent = sf.scene.findObject("pent");
    int triangles = 0;
    double area = 0;
    for (const auto& p : sf.scene.polygons)
        if (p.object == pent) {
            triangles += p.vertexCount == 3 ? 1 : 0;
            area += p.area;
        }
    EXPECT_EQ(triangles, 3);
    EXPECT_NEAR(area, 1.25, 1e-12);
}

TEST_F(LoadScene, NonConvexQuadIsSplitKeepingBothHalvesConvex) {
    // A dart: corner 3 (0.3, 0.3) is reflex; only the diagonal 1-3 keeps both halves convex.
    obj += "o dart\nv 0 0 1\nv 1 0 1\nv 0.3 0.3 1\nv 0 1 1\nf 5 6 7 8\n";  // f: line 13
    const SceneFile sf = load();
    EXPECT_EQ(countWarnings(sf, objFile() + ":13: non-convex face with 4 vertices"), 1)
        << allWarnings(sf);
    const int dart = sf.scene.findObject("dart");
    int triangles = 0;
    double area = 0;
    for (const auto& p : sf.scene.polygons)
        if (p.object == dart) {
            ++triangles;
            EXPECT_EQ(p.vertexCount, 3);
            EXPECT_GT(p.normal.z, 0.999);  // both halves face the way the quad does
            area += p.area;
        }
    EXPECT_EQ(triangles, 2);
    EXPECT_NEAR(area, 0.3, 1e-12);  // 0.5 * (1 * 0.3) * 2
}

TEST_F(LoadScene, NonConvexPentagonWhoseReflexCornerTouchesACut) {
    // Corner (0.5, 0.5) lies on the cut from (0, 1) to (1, 0): cutting there would make a
    // triangle that covers the notch.
    obj += "o notch\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0.5 0.5 1\nv 0 1 1\nf 5 6 7 8 9\n";
    const SceneFile sf = load();
    EXPECT_EQ(countWarnings(sf, objFile() + ":14: non-convex face with 5 vertices"), 1)
        << allWarnings(sf);
    const int notch = sf.scene.findObject("notch");
    double area = 0;
    for (const auto& p : sf.scene.polygons)
        if (p.object == notch) {
            EXPECT_GT(p.normal.z, 0.999);
            // The notch triangle (0.5,0.5)-(1,1)-(0,1) is outside: no centroid in it.
            const Vec3 m = p.centroid();
            EXPECT_FALSE(m.y > m.x && m.y > 1 - m.x) << m.x << " " << m.y;
            area += p.area;
        }
    EXPECT_NEAR(area, 0.75, 1e-12);
}

TEST_F(LoadScene, ObjectsOfTheSameNameInTwoFilesAreOne) {
    scene["geometry"].push_back("more.obj");
    scene["objects"]["floor"]["reflectance"] = {0.2, 0.3, 0.4};
    dir.write("more.obj", "o floor\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const SceneFile sf = load();
    ASSERT_EQ(sf.scene.polygons.size(), 3u);
    EXPECT_EQ(sf.scene.polygons[0].object, sf.scene.polygons[1].object);
    EXPECT_EQ(sf.scene.polygons[1].rho, radiosity::Rgb(0.2, 0.3, 0.4));
    EXPECT_EQ(sf.scene.objects.size(), 2u);  // floor, light:L
}

// ---- the OBJ reader ----------------------------------------------------------------------

relight::ObjFile parse(const std::string& text, const std::string& name = "dir/thing.obj") {
    std::istringstream in(text);
    return relight::parseObj(in, name);
}

TEST(ObjReader, IndexFormsAndNegativeIndices) {
    const auto obj = parse(
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvn 0 0 1\n"
        "f 1/1 2/1/1 3//1 4\n"
        "f -4 -3 -2\n");
    ASSERT_EQ(obj.faces.size(), 2u);
    EXPECT_EQ(obj.faces[0].vertices, (std::vector<int>{0, 1, 2, 3}));
    EXPECT_EQ(obj.faces[0].line, 7);
    EXPECT_EQ(obj.faces[1].vertices, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(obj.faces[1].line, 8);
    EXPECT_TRUE(obj.warnings.empty());
}

TEST(ObjReader, FacesBeforeAnyBlockGoToTheFileStem) {
    const auto obj = parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no a\nf 1 2 3\n");
    ASSERT_EQ(obj.objects, (std::vector<std::string>{"thing", "a"}));
    EXPECT_EQ(obj.faces[0].object, 0);
    EXPECT_EQ(obj.faces[1].object, 1);
}

TEST(ObjReader, GroupsAreObjectsOnlyWithoutO) {
    const auto withO =
        parse("o a\ng part1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng part2\nf 1 2 3\n");
    EXPECT_EQ(withO.objects, (std::vector<std::string>{"a"}));
    const auto onlyG =
        parse("g a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng b\nf 1 2 3\ng a\nf 3 2 1\n");
    EXPECT_EQ(onlyG.objects, (std::vector<std::string>{"a", "b"}));
    ASSERT_EQ(onlyG.faces.size(), 3u);
    EXPECT_EQ(onlyG.faces[2].object, 0);
}

TEST(ObjReader, CrlfCommentsContinuationsAndUnknownStatements) {
    const auto obj = parse(
        "# header\r\n"
        "mtllib x.mtl\r\n"
        "v 0 0 0 # trailing comment\r\n"
        "v +1 0 0 1\r\n"           // a leading '+' and a w coordinate
        "v 0 1 0 0.5 0.5 0.5\r\n"  // vertex colours
        "usemtl red\r\ns off\r\n"
        "f 1 \\\r\n 2 3\r\n"  // continued on the next line; counts as line 8
        "curv 0 1 1 2\r\n");  // line 10
    ASSERT_EQ(obj.faces.size(), 1u);
    EXPECT_EQ(obj.faces[0].line, 8);
    EXPECT_EQ(obj.positions[1], Vec3(1, 0, 0));
    ASSERT_EQ(obj.warnings.size(), 1u);
    EXPECT_TRUE(contains(obj.warnings[0], "dir/thing.obj:10: unknown statement \"curv\""))
        << obj.warnings[0];
}

TEST(ObjReader, ForwardIndicesAreAllowed) {
    const auto obj = parse("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_EQ(obj.faces[0].vertices, (std::vector<int>{0, 1, 2}));
}

TEST(ObjReader, MalformedInputNeverCrashes) {
    const char* bad[] = {
        "f\n",          "v 1 2\n",       "v 1 2 x\n",   "v 0 0 0\nf 1 1\n",
        "f a b c\n",    "v 1e999 0 0\n", "f -5 1 2\n",  "f 0 1 2\n",
        "f 1/ 2/ /3\n", "v nan 0 0\n",   "v inf 0 0\n", "f 99999999999999999999 1 2\n",
        "\\\n",         "v 0 0 0 \\\n",  "f 1 2 3\n"};
    for (const char* text : bad) {
        try {
            parse(text);
        } catch (const InputError& e) {
            EXPECT_TRUE(contains(e.what(), "dir/thing.obj")) << e.what();
        } catch (const std::exception& e) {
            ADD_FAILURE() << "not an InputError for \"" << text << "\": " << e.what();
        }
    }
}

// Found while writing the OBJ fuzz target (the input is kept in its corpus as
// fuzz/corpus/obj/most_negative_vertex_index.obj): the range check negated the index,
// which overflows for -2^63 (UBSan stopped the reader there).
TEST(ObjReader, MostNegativeVertexIndexIsAnError) {
    try {
        parse("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -9223372036854775808\n");
        ADD_FAILURE() << "accepted vertex index -2^63";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(),
                             "dir/thing.obj:4: face references vertex "
                             "-9223372036854775808, but only 3 are defined so far"))
            << e.what();
    }
}

// ---- one bad input per error class ----------------------------------------------------------

TEST_F(LoadScene, UnknownJsonKeysAreErrorsNamingThePath) {
    const std::pair<json::json_pointer, std::string> cases[] = {
        {json::json_pointer("/colour"), "\"colour\": unknown key"},
        {json::json_pointer("/camera/Kx"), "\"camera.Kx\": unknown key"},
        {json::json_pointer("/lights/0/colour"), "\"lights[0].colour\": unknown key"},
        {json::json_pointer("/photos/0/exposure"), "\"photos[0].exposure\": unknown key"},
        {json::json_pointer("/objects/floor/gloss"), "\"objects.floor.gloss\": unknown key"},
    };
    for (const auto& [pointer, expected] : cases) {
        scene = baseScene();
        scene[pointer] = 1;
        const std::string msg = loadError();
        EXPECT_TRUE(contains(msg, jsonFile() + ": key " + expected)) << msg;
    }
}

TEST_F(LoadScene, MissingRequiredKeysAreErrors) {
    for (const char* key : {"geometry", "camera", "lights", "format"}) {
        scene = baseScene();
        scene.erase(key);
        const std::string msg = loadError();
        EXPECT_TRUE(contains(msg, jsonFile() + ": key \"" + std::string(key) + "\": missing"))
            << msg;
    }
}

TEST_F(LoadScene, WrongTypesAndSizesNameTheElement) {
    scene["lights"][0]["vertices"][1] = {0.4, 0.6};
    std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"lights[0].vertices[1]\": expected an array of 3")) << msg;
    scene = baseScene();
    scene["camera"]["width"] = "64";
    msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"camera.width\": expected a number")) << msg;
    scene = baseScene();
    scene["camera"]["K"][2][2] = 2;
    msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"camera.K[2][2]\"")) << msg;
}

TEST_F(LoadScene, CameraRotationMustBeARotation) {
    scene["camera"]["world_to_camera"][0][0] = 1.1;
    std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"camera.world_to_camera\": the left 3x3 block R is not"))
        << msg;
    scene = baseScene();
    scene["camera"]["world_to_camera"][0][0] = -1;  // a reflection
    msg = loadError();
    EXPECT_TRUE(contains(msg, "determinant -1")) << msg;
}

TEST_F(LoadScene, WrongFormatString) {
    scene["format"] = "relight-edit/1";
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, jsonFile() + ": key \"format\": expected \"relight-scene/1\""))
        << msg;
}

TEST_F(LoadScene, JsonSyntaxErrorNamesFileAndLine) {
    write();
    dir.write("scene.json",
              "{\n \"format\": \"relight-scene/1\",\n \"geometry\": [\"box.obj\",]\n}\n");
    try {
        loadScene(dir.path());
        ADD_FAILURE() << "accepted bad JSON";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), jsonFile() + ": invalid JSON")) << e.what();
        EXPECT_TRUE(contains(e.what(), "line 3")) << e.what();
    }
}

TEST_F(LoadScene, DuplicateJsonKeyIsAnError) {
    write();
    std::string text = scene.dump(1);
    text.insert(text.find("\"name\": \"L\""), "\"name\": \"X\",\n");
    dir.write("scene.json", text);
    try {
        loadScene(dir.path());
        ADD_FAILURE() << "accepted a duplicate key";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), "key \"lights[0].name\": duplicate key")) << e.what();
    }
}

TEST_F(LoadScene, MissingSceneJson) {
    try {
        loadScene(dir.path());
        ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), jsonFile() + ": file not found")) << e.what();
    }
}

TEST_F(LoadScene, MissingObjFileIsNamed) {
    scene["geometry"] = {"nothere.obj"};
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"geometry[0]\"")) << msg;
    EXPECT_TRUE(contains(msg, (dir.path() / "nothere.obj").string() + "\" not found")) << msg;
}

TEST_F(LoadScene, ObjIndexOutOfRangeNamesTheLine) {
    obj += "f 1 2 9\n";  // line 8
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, objFile() + ":8: face references vertex 9, but only 4 are defined"))
        << msg;
}

TEST_F(LoadScene, ObjBadNumberNamesTheLine) {
    obj = "o floor\nv 0 0 0\nv 1 0,5 0\n";
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, objFile() + ":3: bad number \"0,5\"")) << msg;
}

TEST_F(LoadScene, ObjFaceWithTwoVerticesIsAnError) {
    obj += "f 1 2\n";
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, objFile() + ":8: face needs at least 3 vertices")) << msg;
}

TEST_F(LoadScene, NaNCoordinateIsAnErrorWithItsLine) {
    obj = "o floor\nv 0 0 0\nv 1 0 0\nv 1 nan 0\nf 1 2 3\n";
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, objFile() + ":4: vertex coordinate \"nan\" is not finite")) << msg;
}

TEST_F(LoadScene, NonPlanarQuadIsSplitWithWarning) {
    // Corner 3 is 5 cm above the plane of the others; diagonal 2-4 (1.56 m) is shorter
    // than 1-3 (2.12 m).
    obj += "o bent\nv 0 0 1\nv 1.2 0 1\nv 1.5 1.5 1.05\nv 0 1 1\nf 5 6 7 8\n";  // f: line 13
    const SceneFile sf = load();
    EXPECT_EQ(countWarnings(sf, objFile() + ":13: non-planar polygon"), 1) << allWarnings(sf);
    EXPECT_EQ(countWarnings(sf, "split into 2 triangles along its shorter diagonal"), 1);
    const int bent = sf.scene.findObject("bent");
    std::vector<const radiosity::Polygon*> halves;
    for (const auto& p : sf.scene.polygons)
        if (p.object == bent) halves.push_back(&p);
    ASSERT_EQ(halves.size(), 2u);
    for (const auto* p : halves) {
        EXPECT_EQ(p->vertexCount, 3);
        EXPECT_GT(p->normal.z, 0.9);
        // Both halves hold the shorter diagonal's corners (1.2 0 1) and (0 1 1).
        int onDiagonal = 0;
        for (int k = 0; k < 3; ++k)
            onDiagonal += (p->v[static_cast<size_t>(k)] == Vec3(1.2, 0, 1) ||
                           p->v[static_cast<size_t>(k)] == Vec3(0, 1, 1))
                              ? 1
                              : 0;
        EXPECT_EQ(onDiagonal, 2);
    }
}

TEST_F(LoadScene, DegenerateFaceIsDroppedWithWarning) {
    obj += "v 2 0 0\nf 1 2 5\n";  // collinear: line 9
    const SceneFile sf = load();
    EXPECT_EQ(countWarnings(sf, objFile() + ":9: degenerate face"), 1) << allWarnings(sf);
    EXPECT_EQ(sf.scene.polygons.size(), 2u);  // the floor and the light only
}

TEST_F(LoadScene, ZeroAreaLightIsAnError) {
    scene["lights"][0]["vertices"] = {{0.4, 0.4, 0.9}, {0.5, 0.5, 0.9}, {0.6, 0.6, 0.9}};
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, jsonFile() + ": key \"lights[0].vertices\"")) << msg;
    EXPECT_TRUE(contains(msg, "degenerate")) << msg;
}

TEST_F(LoadScene, NonPlanarAndNonConvexLightsAreErrors) {
    scene["lights"][0]["vertices"][2] = {0.6, 0.6, 0.95};
    std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"lights[0].vertices\"") && contains(msg, "non-planar")) << msg;
    scene = baseScene();
    scene["lights"][0]["vertices"][2] = {0.45, 0.45, 0.9};
    msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"lights[0].vertices\"") && contains(msg, "not convex")) << msg;
    scene = baseScene();
    scene["lights"][0]["vertices"] = {{0.4, 0.4, 0.9}, {0.4, 0.6, 0.9}};
    msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"lights[0].vertices\": expected an array of at least 3"))
        << msg;
}

TEST_F(LoadScene, LightsOnNamingAnUnknownLight) {
    scene["photos"][0]["lights_on"] = {"L", "Q"};
    const std::string msg = loadError();
    EXPECT_TRUE(
        contains(msg, jsonFile() + ": key \"photos[0].lights_on[1]\": no light named \"Q\""))
        << msg;
}

TEST_F(LoadScene, NegativeRadianceIsAnError) {
    scene["lights"][0]["radiance"] = {1, -0.5, 1};
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, jsonFile() + ": key \"lights[0].radiance[1]\": radiance must not"))
        << msg;
    scene["lights"][0]["radiance"] = "guess";
    EXPECT_TRUE(contains(loadError(), "key \"lights[0].radiance\""));
}

TEST_F(LoadScene, UnsupportedLightTypeAndDuplicateNames) {
    scene["lights"][0]["type"] = "spot";
    std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"lights[0].type\": light type spot not supported")) << msg;
    scene = baseScene();
    scene["lights"].push_back(scene["lights"][0]);
    msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"lights[1].name\": duplicate light name \"L\"")) << msg;
}

TEST_F(LoadScene, TheFormatsOtherLightTypesAreRead) {
    // docs/scene-format.md's sun, point and environment lights, as the format writes them:
    // one light per component (a sky's 9 coefficients are 9 lights of one name), no faces,
    // their strengths as nominal radiances.
    scene = baseScene();
    scene["lights"].push_back(json::parse(R"({"name": "sun", "type": "sun",
        "direction": [0.4, -0.3, 0.5], "angle": 0.53, "irradiance": [3, 2.9, 2.7]})"));
    scene["lights"].push_back(json::parse(
        R"({"name": "P", "type": "point", "position": [0.5, 0.5, 0.5], "intensity": [1, 2, 3]})"));
    json sky = {{"name", "sky"}, {"type", "environment"}, {"sh9", json::array()}};
    for (int k = 0; k < 9; ++k) sky["sh9"].push_back({0.1 * k, 0.2, -0.05});
    scene["lights"].push_back(sky);
    const SceneFile sf = load();
    const auto& lights = sf.scene.lights;
    ASSERT_EQ(lights.size(), 1u + 1 + 1 + 9);
    EXPECT_TRUE(lights[1].polygons.empty());
    ASSERT_TRUE(lights[1].emitter);
    EXPECT_STREQ(lights[1].emitter->type(), "sun");
    EXPECT_EQ(sf.nominalRadiance[1].g, 2.9);
    EXPECT_STREQ(lights[2].emitter->type(), "point");
    EXPECT_EQ(sf.nominalRadiance[2].b, 3.0);
    for (int k = 0; k < 9; ++k) {
        EXPECT_EQ(lights[3 + k].name, "sky");
        EXPECT_EQ(lights[3 + k].component, k);
        EXPECT_EQ(lights[3 + k].emitter, lights[3].emitter);
        EXPECT_EQ(sf.nominalRadiance[3 + k].r, 0.1 * k);
        EXPECT_EQ(sf.nominalRadiance[3 + k].b, -0.05);
    }
}

TEST_F(LoadScene, TheOtherLightTypesBadFieldsAreNamed) {
    const std::vector<std::pair<json, std::string>> bad = {
        {json::parse(R"({"name": "sun", "type": "sun", "direction": [0, 0, 0], "angle": 0.53,
                         "irradiance": [1, 1, 1]})"),
         "key \"lights[1]\": sun 'sun': direction must be finite and non-zero"},
        {json::parse(R"({"name": "sun", "type": "sun", "direction": [0, 0, 1], "angle": 0.53,
                         "irradiance": "guess"})"),
         "key \"lights[1].irradiance\": expected an RGB array or \"estimate\", got \"guess\""},
        {json::parse(R"({"name": "P", "type": "point", "position": [0, 0, 1],
                         "intensity": "estimate"})"),
         "key \"lights[1].intensity\": \"estimate\" is not supported here"},
        {json::parse(R"({"name": "P", "type": "point", "position": [0, 0, 1],
                         "intensity": [1, -1, 1]})"),
         "key \"lights[1].intensity[1]\": must not be negative"},
        {json::parse(R"({"name": "sky", "type": "environment", "sh9": "fit"})"),
         "key \"lights[1].sh9\": expected 9 RGB rows or \"estimate\", got \"fit\""},
        {json::parse(R"({"name": "sky", "type": "environment", "sh9": [[1, 1, 1]]})"),
         "key \"lights[1].sh9\""},
        {json::parse(R"({"name": "P", "type": "point", "position": [0, 0, 1],
                         "intensity": [1, 1, 1], "direction": [0, 0, 1]})"),
         "key \"lights[1].direction\""},
        {json::parse(R"({"name": "X", "type": "spot"})"),
         "key \"lights[1].type\": light type spot not supported"},
    };
    for (const auto& [light, expected] : bad) {
        scene = baseScene();
        scene["lights"].push_back(light);
        const std::string msg = loadError();
        EXPECT_TRUE(contains(msg, jsonFile() + ": " + expected)) << msg;
    }
}

TEST_F(LoadScene, ASunsAndASkysEstimateIsReadAsZeroStrengthsFlagged) {
    // docs/scene-format.md: a sun's "irradiance" and a sky's "sh9" may be "estimate"; every
    // component of such a light is flagged, its nominal strength 0 until the fit.
    scene = baseScene();
    scene["lights"].push_back(json::parse(R"({"name": "sun", "type": "sun",
        "direction": [0.4, -0.3, 0.5], "angle": 0.53, "irradiance": "estimate"})"));
    scene["lights"].push_back(
        json::parse(R"({"name": "sky", "type": "environment", "sh9": "estimate"})"));
    const SceneFile sf = load();
    ASSERT_EQ(sf.scene.lights.size(), 1u + 1 + 9);
    EXPECT_FALSE(sf.estimateRadiance[0]);
    for (size_t l = 1; l < sf.scene.lights.size(); ++l) {
        EXPECT_TRUE(sf.estimateRadiance[l]) << l;
        EXPECT_EQ(sf.nominalRadiance[l], radiosity::Rgb{}) << l;
    }
}

TEST_F(LoadScene, ReflectanceOfOneIsClampedWithWarning) {
    scene["objects"]["floor"]["reflectance"] = {1.0, 0.5, 0.2};
    const SceneFile sf = load();
    EXPECT_EQ(countWarnings(sf, jsonFile() + ": key \"objects.floor.reflectance\": reflectance 1 "
                                             "clamped to 0.99"),
              1)
        << allWarnings(sf);
    EXPECT_EQ(sf.scene.polygons[0].rho, radiosity::Rgb(0.99, 0.5, 0.2));
    EXPECT_EQ(*sf.objectSettings.at("floor").reflectance, radiosity::Rgb(0.99, 0.5, 0.2));
}

TEST_F(LoadScene, ReflectanceOutsideUnitRangeIsAnError) {
    scene["objects"]["floor"]["reflectance"] = {0.5, 1.5, 0.2};
    std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"objects.floor.reflectance[1]\": must be in [0, 1]")) << msg;
    scene = baseScene();
    scene["average_reflectance"] = 1.0;
    msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"average_reflectance\": must be in [0, 1)")) << msg;
}

TEST_F(LoadScene, ObjectsEntryForAnUnknownObject) {
    scene["objects"]["ghost"] = {{"removable", true}};
    const std::string msg = loadError();
    EXPECT_TRUE(contains(msg, "key \"objects.ghost\": no object of this name")) << msg;
}

TEST_F(LoadScene, OverflowingNumberIsNotFinite) {
    write();
    std::string text = scene.dump(1);
    const std::string from = "\"width\": 64";
    text.replace(text.find(from), from.size(), "\"width\": 1e999");
    dir.write("scene.json", text);
    try {
        loadScene(dir.path());
        ADD_FAILURE() << "accepted 1e999";
    } catch (const InputError& e) {
        EXPECT_TRUE(contains(e.what(), jsonFile())) << e.what();
    }
}

/// Replaces every value of the base scene, one at a time, by values of the wrong type:
/// each load must either succeed or throw InputError, never anything else.
TEST_F(LoadScene, NoValueOfTheWrongTypeCrashes) {
    std::vector<json::json_pointer> pointers;
    auto collect = [&](auto&& self, const json& j, const json::json_pointer& at) -> void {
        if (!at.empty()) pointers.push_back(at);
        if (j.is_object())
            for (auto it = j.begin(); it != j.end(); ++it) self(self, it.value(), at / it.key());
        if (j.is_array())
            for (size_t i = 0; i < j.size(); ++i) self(self, j[i], at / i);
    };
    collect(collect, baseScene(), json::json_pointer());
    const json replacements[] = {
        nullptr, true, -1, 0, 1e300, "x", json::array(), json::object(), json::array({1, 2})};
    int loads = 0;
    for (const auto& pointer : pointers) {
        for (const json& value : replacements) {
            scene = baseScene();
            scene[pointer] = value;
            write();
            try {
                loadScene(dir.path());
            } catch (const InputError&) {
            } catch (const std::exception& e) {
                ADD_FAILURE() << pointer.to_string() << " = " << value.dump() << ": " << e.what();
            }
            ++loads;
        }
    }
    EXPECT_GT(loads, 300);
}

}  // namespace
