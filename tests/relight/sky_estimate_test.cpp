// The sun and sky "estimate" end to end (relight/pipeline/sky_estimate.h): a photo rendered
// by the engine's own radiosity from known coefficients and a known sun is given back by the
// fit, through scene.json's "estimate", the item buffer, the per-pixel direct light and the
// alternation with the reflectance and the indirect light.
#include "relight/pipeline/sky_estimate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>

#include "radiosity/sh9.h"
#include "relight/errors.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/relighting.h"
#include "temp_dir.h"
#include "tests/support/skies.h"

namespace relight {
namespace {

using nlohmann::json;
using radiosity::Rgb;
using radiosity::Vec3;

/// Nine cubes of 0.6 m, each turned its own way (a fixed seed), floating in a 3 x 3 grid in
/// front of the camera: faces towards every direction, the sky below the horizon included,
/// so that all 9 coefficients are determined; each cube its own object, as Wen's one
/// albedo per object.
std::string cubesObj() {
    std::mt19937 rng(7);
    std::normal_distribution<double> g;
    std::ostringstream o;
    int base = 1;
    for (int c = 0; c < 9; ++c) {
        const Vec3 axis = glm::normalize(Vec3{g(rng), g(rng), g(rng)});
        const double angle = 1.0 + 0.6 * c;
        const Vec3 centre{-1.5 + 1.5 * (c % 3), 0.0, 1.5 * (c / 3)};
        o << "o cube" << c << "\n";
        for (int k = 0; k < 8; ++k) {
            const Vec3 p{(k & 1) ? 0.3 : -0.3, (k & 2) ? 0.3 : -0.3, (k & 4) ? 0.3 : -0.3};
            // Rodrigues' rotation of p about `axis`.
            const Vec3 r = p * std::cos(angle) + glm::cross(axis, p) * std::sin(angle) +
                           axis * glm::dot(axis, p) * (1 - std::cos(angle));
            const Vec3 v = centre + r;
            o << "v " << v.x << " " << v.y << " " << v.z << "\n";
        }
        // Counter-clockwise seen from outside: -x, +x, -y, +y, -z, +z.
        const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
        for (const auto& f : faces)
            o << "f " << base + f[0] << " " << base + f[1] << " " << base + f[2] << " "
              << base + f[3] << "\n";
        base += 8;
    }
    return o.str();
}

const Rgb kSun{3.0, 2.8, 2.5};

json sceneJson(bool estimate) {
    // Camera at (0, -6, 1.5) looking along +y (OpenCV: x right, y down, z forward).
    json s = {{"format", "relight-scene/1"},
              {"geometry", {"cubes.obj"}},
              {"camera",
               {{"width", 80},
                {"height", 60},
                {"K", {{60.0, 0.0, 39.5}, {0.0, 60.0, 29.5}, {0.0, 0.0, 1.0}}},
                {"world_to_camera", {{1, 0, 0, 0}, {0, 0, -1, 1.5}, {0, 1, 0, 6}}}}},
              {"photos", {{{"file", "photo.exr"}, {"lights_on", {"sun", "sky"}}}}},
              {"average_reflectance", 0.5}};
    json sky = json::array();
    for (const Rgb& c : radiosity::test::clearSky().c) sky.push_back({c.r, c.g, c.b});
    s["lights"] = {
        {{"name", "sun"},
         {"type", "sun"},
         {"direction", {0.3, -0.5, 0.8}},
         {"angle", 0.53},
         {"irradiance", estimate ? json("estimate") : json{kSun.r, kSun.g, kSun.b}}},
        {{"name", "sky"}, {"type", "environment"}, {"sh9", estimate ? json("estimate") : sky}}};
    return s;
}

SceneFile parse(const test::TempDir& dir, const json& j) {
    std::istringstream in(j.dump());
    return parseScene(in, dir.path());
}

constexpr int kSpp = 4;

/// The photo: the engine's radiance image (E + rho H) / pi of the given lights' solution.
void renderPhoto(const test::TempDir& dir) {
    const SceneFile sf = parse(dir, sceneJson(false));
    radiosity::HierarchicalSolver solver(sf.scene);
    solver.solve();
    const ItemBuffer items = castItemBuffer(sf.camera, solver.scene(), solver.visibility(), kSpp);
    LightingBuffer buf = computeLightingBuffer(items, solver);
    updateIndirect(buf, solver);
    writeImage(dir.path() / "photo.exr", renderRadiosity(items, buf, solver.scene()));
}

TEST(SkyEstimate, APhotoOfKnownLightsGivesThemBack) {
    const test::TempDir dir("sky_estimate");
    dir.write("cubes.obj", cubesObj());
    renderPhoto(dir);
    SceneFile sf = parse(dir, sceneJson(true));
    ASSERT_TRUE(hasSkyEstimate(sf));
    radiosity::HierarchicalSolver solver(sf.scene);
    const ItemBuffer items = castItemBuffer(sf.camera, solver.scene(), solver.visibility(), kSpp);
    const SkyEstimateReport rep =
        estimateSkyFromPhoto(sf, solver, items, loadFirstPhoto(sf), SkyEstimateOptions{});
    ASSERT_EQ(rep.skyName, "sky");
    ASSERT_EQ(rep.sunName, "sun");
    // The same item buffer and rays give the fit the photo's own direct light; what differs
    // is the indirect light (the fit's solver was refined for its first guess) and the
    // ridge's pull on the least determined directions. Measured: 0.004 at most on the
    // coefficients (0.3 % of the DC term), 1e-4 on the sun; bounds of 1 % of each leave
    // room for other rays, and a wrong column scale (pi), a lost indirect term (~10 %) or a
    // sun taken for sky would all exceed them.
    const radiosity::Sh9Rgb truth = radiosity::test::clearSky();
    for (int k = 0; k < radiosity::kSh9Count; ++k)
        std::printf("L%d fitted %.4f %.4f %.4f, true %.4f %.4f %.4f\n", k,
                    rep.sky.c[static_cast<size_t>(k)].r, rep.sky.c[static_cast<size_t>(k)].g,
                    rep.sky.c[static_cast<size_t>(k)].b, truth.c[static_cast<size_t>(k)].r,
                    truth.c[static_cast<size_t>(k)].g, truth.c[static_cast<size_t>(k)].b);
    std::printf("sun fitted %.4f %.4f %.4f; %d pixels, rank %d of %d\n", rep.sun.r, rep.sun.g,
                rep.sun.b, rep.pixels, rep.rank, rep.unknowns);
    const double tol = 0.01 * truth.c[0].maxComponent();
    for (int k = 0; k < radiosity::kSh9Count; ++k)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(rep.sky.c[static_cast<size_t>(k)][c], truth.c[static_cast<size_t>(k)][c],
                        tol)
                << "L" << k << " channel " << c;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rep.sun[c], kSun[c], 0.01 * kSun[c]) << c;
    // The estimate is the lights' strength from here on.
    EXPECT_EQ(sf.nominalRadiance[0], rep.sun);
    EXPECT_EQ(sf.nominalRadiance[1], rep.sky.c[0]);
}

TEST(SkyEstimate, TwoEstimatedSkiesAreRefusedNamingTheKey) {
    const test::TempDir dir("sky_estimate");
    dir.write("cubes.obj", cubesObj());
    json j = sceneJson(true);
    j["lights"].push_back({{"name", "sky2"}, {"type", "environment"}, {"sh9", "estimate"}});
    j["photos"][0]["lights_on"].push_back("sky2");
    SceneFile sf = parse(dir, j);
    radiosity::HierarchicalSolver solver(sf.scene);
    const ItemBuffer items = castItemBuffer(sf.camera, solver.scene(), solver.visibility(), 1);
    const Image photo(80, 60);
    try {
        estimateSkyFromPhoto(sf, solver, items, photo);
        FAIL() << "two estimated skies accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("key \"lights[2].sh9\": only one sky"),
                  std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace relight
