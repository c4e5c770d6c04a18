// Tests of real lamps added to scene.json (relight/io/scene_lights.h): the quad's shape and
// side, the lamps loaded back as the scene's lights (an "estimate" one, one off in the
// photo), and a refused lamp that leaves scene.json as it was.
#include "relight/io/scene_lights.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "relight/io/scene_file.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using radiosity::Vec3;
using relight::test::TempDir;

// A w x h rectangle about the centre, counter-clockwise seen from the normal's side, for
// a floor, a wall and a slanted face.
TEST(SceneLamps, QuadIsTheRectangleFacingTheNormal) {
    for (const Vec3& normal : {Vec3(0, 0, -1), Vec3(1, 0, 0), Vec3(0.3, -0.5, 0.8)}) {
        const Vec3 centre(1, 2, 3);
        const auto q = relight::lampQuad(centre, normal * 2.0, 0.4, 0.1);
        ASSERT_EQ(q.size(), 4u);
        const Vec3 n = glm::normalize(normal);
        // (v1 - v0) x (v2 - v0): the format's face normal, along n, of length the area x 2.
        const Vec3 cross = glm::cross(q[1] - q[0], q[2] - q[0]);
        EXPECT_NEAR(glm::dot(cross, n), 0.04, 1e-12);
        EXPECT_NEAR(glm::length(q[1] - q[0]), 0.4, 1e-12);
        EXPECT_NEAR(glm::length(q[3] - q[0]), 0.1, 1e-12);
        EXPECT_NEAR(glm::dot(q[1] - q[0], q[3] - q[0]), 0, 1e-12);
        const Vec3 mean = (q[0] + q[1] + q[2] + q[3]) * 0.25;
        EXPECT_NEAR(glm::length(mean - centre), 0, 1e-12);
        for (const Vec3& c : q) EXPECT_NEAR(glm::dot(c - centre, n), 0, 1e-12);
    }
}

/// A copy of the room's inputs in `dir`.
void copyRoom(const TempDir& dir) {
    for (const char* f : {"scene.json", "room.obj", "photo.exr"})
        fs::copy_file(fs::path(RELIGHT_DATA_DIR) / "room" / f, dir.path() / f);
}

TEST(SceneLamps, AddedLampsLoadAsTheScenesLights) {
    TempDir dir("scene_lamps");
    copyRoom(dir);
    const relight::SceneFile before = relight::loadScene(dir.path());
    relight::RealLamp estimated{"desk", relight::lampQuad({1, 1, 2.4}, {0, 0, -1}, 0.3, 0.2),
                                std::nullopt, true};
    relight::RealLamp given{"shelf", relight::lampQuad({0.5, 0.5, 1}, {1, 0, 0}, 0.2, 0.2),
                            radiosity::Rgb{2, 3, 4}, false};
    relight::addLampsToScene(dir.path(), {estimated, given});
    const relight::SceneFile after = relight::loadScene(dir.path());
    const size_t n = before.scene.lights.size();
    ASSERT_EQ(after.scene.lights.size(), n + 2);
    EXPECT_EQ(after.scene.lights[n].name, "desk");
    EXPECT_TRUE(after.estimateRadiance[n]);
    EXPECT_FALSE(after.estimateRadiance[n + 1]);
    EXPECT_EQ(after.nominalRadiance[n + 1], (radiosity::Rgb{2, 3, 4}));
    EXPECT_TRUE(after.lightOnInPhoto(n));
    EXPECT_FALSE(after.lightOnInPhoto(n + 1));
    // Everything else as it was: the camera, the objects, the photo.
    EXPECT_EQ(after.camera.fx, before.camera.fx);
    EXPECT_EQ(after.objectSettings.size(), before.objectSettings.size());
    EXPECT_EQ(after.scene.polygons.size(), before.scene.polygons.size() + 2);
}

TEST(SceneLamps, RefusedLampLeavesSceneJsonAsItWas) {
    TempDir dir("scene_lamps");
    copyRoom(dir);
    auto read = [&] {
        std::ifstream in(dir.path() / "scene.json");
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    };
    const std::string original = read();
    // "A" is one of the room's lights.
    relight::RealLamp taken{"A", relight::lampQuad({1, 1, 2.4}, {0, 0, -1}, 0.3, 0.2), std::nullopt,
                            true};
    try {
        relight::addLampsToScene(dir.path(), {taken});
        ADD_FAILURE() << "a name already taken was accepted";
    } catch (const relight::InputError& e) {
        EXPECT_NE(std::string(e.what()).find("scene.json: key \"lights[4].name\": duplicate light "
                                             "name \"A\""),
                  std::string::npos)
            << e.what();
    }
    EXPECT_EQ(read(), original);
}

}  // namespace
