// Tests of the undistortion (relight/io/undistort.h) and of the COLMAP import
// (relight/io/colmap_import.h): a grid photographed through a SIMPLE_RADIAL lens comes out
// with straight lines where the pinhole camera puts them; the room imported from its camera
// written as a COLMAP model loads as the room; bad inputs are errors naming their file and
// leave the output folder as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "relight/io/colmap_camera.h"
#include "relight/io/colmap_import.h"
#include "relight/io/colmap_model.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/io/undistort.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using relight::PixelGrid;
using relight::test::TempDir;
namespace colmap = relight::colmap;
using radiosity::Vec3;

/// A SIMPLE_RADIAL camera (COLMAP's numbers) and its lens; barrel distortion for k < 0.
colmap::Lens simpleRadial(int width, int height, double f, double k) {
    colmap::Camera c;
    c.model = "SIMPLE_RADIAL";
    c.width = width;
    c.height = height;
    c.params = {f, width / 2.0, height / 2.0, k};
    return colmap::lensOf(c);
}

/// The grid of lines x = 0.1 m and y = 0.1 n (in the pinhole's x = Xc/Zc, y = Yc/Zc) seen
/// through `lens`: each line a smooth ridge (a Gaussian across it, sigma 1.2 pinhole
/// pixels), so that where it lies can be measured to a small fraction of a pixel.
PixelGrid photographGrid(const colmap::Lens& lens) {
    PixelGrid g{lens.width, lens.height, 1, {}};
    g.values.resize(static_cast<size_t>(g.width) * g.height);
    auto ridge = [&](double t) {
        const double d = (t - 0.1 * std::round(t / 0.1)) * lens.fx / 1.2;
        return std::exp(-0.5 * d * d);
    };
    for (int v = 0; v < g.height; ++v)
        for (int u = 0; u < g.width; ++u) {
            double x = 0, y = 0;
            EXPECT_TRUE(lens.undistort((u - lens.cx) / lens.fx, (v - lens.cy) / lens.fy, x, y));
            g.values[static_cast<size_t>(v) * g.width + u] =
                static_cast<float>(std::max(ridge(x), ridge(y)));
        }
    return g;
}

/// The largest distance, in pixels, between where the vertical grid lines are found in
/// `image` (the centroid of each row's values within 5 pixels) and where `pinhole` puts
/// them (u = fx 0.1 m + cx), over the rows between the horizontal lines.
double verticalLineError(const PixelGrid& image, const colmap::Lens& pinhole) {
    double worst = 0;
    for (int m = -20; m <= 20; ++m) {
        const double expected = pinhole.fx * 0.1 * m + pinhole.cx;
        if (expected < 6 || expected > image.width - 7) continue;
        for (int v = 6; v < image.height - 6; ++v) {
            const double y = (v - pinhole.cy) / pinhole.fy;
            // Rows on or near a horizontal line are bright across: no vertical line to find.
            if (std::abs(y - 0.1 * std::round(y / 0.1)) * pinhole.fy < 6) continue;
            double sum = 0, moment = 0;
            for (int u = static_cast<int>(std::round(expected)) - 5;
                 u <= static_cast<int>(std::round(expected)) + 5; ++u) {
                const double value = image.values[static_cast<size_t>(v) * image.width + u];
                sum += value;
                moment += value * u;
            }
            if (!(sum > 0)) return 1e9;  // no line where one should be
            worst = std::max(worst, std::abs(moment / sum - expected));
        }
    }
    return worst;
}

// A grid seen through a SIMPLE_RADIAL lens with strong barrel distortion (k = -0.08: lines
// near the border bow by several pixels) becomes straight lines, each at the column the
// undistorted pinhole camera puts it: within 0.05 px (the bilinear resampling of a ridge
// 1.2 px wide moves its centroid by a few hundredths of a pixel; 0.03 here).
TEST(ColmapUndistort, SimpleRadialGridBecomesStraightLines) {
    const colmap::Lens lens = simpleRadial(320, 240, 200, -0.08);
    const PixelGrid photo = photographGrid(lens);
    // The control: read as if it were a pinhole photo, the lines are far from straight.
    colmap::Lens asPinhole = lens;
    asPinhole.k1 = 0;
    EXPECT_GT(verticalLineError(photo, asPinhole), 2.0);

    const colmap::Lens pinhole = relight::undistortedLens(lens, "test");
    EXPECT_LT(pinhole.fx, lens.fx);  // barrel: a wider view keeps the edges' middles
    EXPECT_DOUBLE_EQ(pinhole.fx / pinhole.fy, lens.fx / lens.fy);
    EXPECT_EQ(pinhole.cx, lens.cx);
    const PixelGrid out = relight::undistortPixels(photo, lens, pinhole);
    EXPECT_LT(verticalLineError(out, pinhole), 0.05);
}

// The fitted pinhole sees only the photo: every border pixel of the undistorted photo comes
// from inside the distorted one's outermost pixel centres (no black border; to 1e-3 px, as
// the fit samples the photo's edges one pixel apart), and one of them from that edge itself
// (the view is no narrower than it must be). Barrel and
// pincushion, radial and OPENCV lenses.
TEST(ColmapUndistort, FittedPinholeSeesOnlyThePhotoAndAllOfItsWidthOrHeight) {
    std::vector<colmap::Lens> lenses = {simpleRadial(320, 240, 200, -0.08),
                                        simpleRadial(320, 240, 200, 0.1)};
    colmap::Lens opencv = simpleRadial(400, 300, 300, -0.1);
    opencv.k2 = 0.02;
    opencv.p1 = 0.002;
    opencv.p2 = -0.001;
    opencv.cx += 7;
    lenses.push_back(opencv);
    for (const colmap::Lens& lens : lenses) {
        const colmap::Lens pinhole = relight::undistortedLens(lens, "test");
        double closest = 1e9;
        auto check = [&](int u, int v) {
            double xd = 0, yd = 0;
            lens.distort((u - pinhole.cx) / pinhole.fx, (v - pinhole.cy) / pinhole.fy, xd, yd);
            const double us = lens.fx * xd + lens.cx, vs = lens.fy * yd + lens.cy;
            EXPECT_GE(us, -1e-3);
            EXPECT_LE(us, lens.width - 1 + 1e-3);
            EXPECT_GE(vs, -1e-3);
            EXPECT_LE(vs, lens.height - 1 + 1e-3);
            closest = std::min({closest, us, vs, lens.width - 1 - us, lens.height - 1 - vs});
        };
        for (int u = 0; u < lens.width; ++u) check(u, 0), check(u, lens.height - 1);
        for (int v = 0; v < lens.height; ++v) check(0, v), check(lens.width - 1, v);
        EXPECT_LT(closest, 0.05);
    }
}

// A world point seen through a distorted COLMAP camera (COLMAP's equations: the quaternion's
// rotation, then the lens distortion, then f, c with the top-left pixel's centre at 0.5)
// lands at the pixel of the distorted photo that the undistorted photo reads for the point's
// pixel in the imported pinhole camera: the whole chain, half-pixel shift included.
TEST(ColmapUndistort, DistortedProjectionMatchesTheImportedPinholeAndResampling) {
    colmap::Camera radial{1, "SIMPLE_RADIAL", 640, 480, {500, 321.3, 238.9, -0.07}, ""};
    colmap::Camera opencv{
        2, "OPENCV", 640, 480, {510, 495, 318.2, 243.1, -0.08, 0.01, 0.0015, -0.001}, ""};
    colmap::Image image;
    image.qvec = {0.9, 0.1, -0.2, 0.05};
    image.tvec = {0.1, -0.2, 2.5};
    for (const colmap::Camera& camera : {radial, opencv}) {
        SCOPED_TRACE(camera.model);
        const colmap::Lens lens = colmap::lensOf(camera);
        const colmap::Lens pinhole = relight::undistortedLens(lens, "test");
        const relight::Camera imported = colmap::sceneCamera(image, pinhole);
        const bool simple = camera.model == "SIMPLE_RADIAL";
        const std::vector<double>& p = camera.params;
        for (double wx = -0.6; wx <= 0.6; wx += 0.3)
            for (double wy = -0.4; wy <= 0.4; wy += 0.2) {
                const Vec3 world(wx, wy, 0.3);
                const Vec3 xc = colmap::rotationFromQuaternion(image.qvec, "test") * world +
                                Vec3(image.tvec[0], image.tvec[1], image.tvec[2]);
                const double u = xc.x / xc.z, v = xc.y / xc.z, r2 = u * u + v * v;
                double du = 0, dv = 0;
                if (simple) {
                    du = u * p[3] * r2;
                    dv = v * p[3] * r2;
                } else {
                    const double radialTerm = p[4] * r2 + p[5] * r2 * r2;
                    du = u * radialTerm + 2 * p[6] * u * v + p[7] * (r2 + 2 * u * u);
                    dv = v * radialTerm + 2 * p[7] * u * v + p[6] * (r2 + 2 * v * v);
                }
                const double fx = p[0], fy = simple ? p[0] : p[1];
                const double cx = simple ? p[1] : p[2], cy = simple ? p[2] : p[3];
                const double uColmap = fx * (u + du) + cx, vColmap = fy * (v + dv) + cy;
                // The imported camera's pixel, and where the resampling reads it from.
                double ui = 0, vi = 0, depth = 0;
                ASSERT_TRUE(imported.project(world, ui, vi, depth));
                double xd = 0, yd = 0;
                lens.distort((ui - pinhole.cx) / pinhole.fx, (vi - pinhole.cy) / pinhole.fy, xd,
                             yd);
                EXPECT_NEAR(lens.fx * xd + lens.cx + 0.5, uColmap, 1e-9);
                EXPECT_NEAR(lens.fy * yd + lens.cy + 0.5, vColmap, 1e-9);
            }
    }
}

// ---- the import -------------------------------------------------------------------------

/// A COLMAP model of `scene`'s camera (plus another image) in <dir>/sparse, its photo in
/// <dir>/images, and the import's options for it.
relight::ColmapImportOptions roomModel(const TempDir& dir, bool binary) {
    const fs::path room = fs::path(RELIGHT_DATA_DIR) / "room";
    const relight::SceneFile sf = relight::loadScene(room);
    colmap::Model model;
    model.cameras[1] = colmap::colmapCamera(sf.camera, 1);
    model.images.push_back(colmap::colmapImage(sf.camera, 5, 1, "shots/room.exr"));
    fs::create_directories(dir.path() / "sparse");
    fs::create_directories(dir.path() / "images" / "shots");
    binary ? colmap::writeBinary(dir.path() / "sparse", model)
           : colmap::writeText(dir.path() / "sparse", model);
    fs::copy_file(room / "photo.exr", dir.path() / "images" / "shots" / "room.exr");
    relight::ColmapImportOptions o;
    o.sparseDir = dir.path() / "sparse";
    o.image = "shots/room.exr";
    o.imagesDir = dir.path() / "images";
    o.mesh = room / "room.obj";
    o.lights = room / "scene.json";
    o.objects = room / "scene.json";
    o.averageReflectance = 0.6;
    o.output = dir.path() / "out";
    return o;
}

// The room's camera written as a COLMAP model and imported with the room's mesh, lights and
// objects loads as the room: the same camera to 1e-9, lights, objects, photo.
TEST(ColmapImport, RoomImportedLoadsAsTheRoom) {
    for (const bool binary : {false, true}) {
        TempDir dir("colmap_import");
        const relight::ColmapImportResult r = relight::importColmap(roomModel(dir, binary));
        EXPECT_FALSE(r.undistorted);
        const relight::SceneFile room = relight::loadScene(fs::path(RELIGHT_DATA_DIR) / "room");
        const relight::SceneFile imported = relight::loadScene(dir.path() / "out");
        const relight::Camera &a = room.camera, &b = imported.camera;
        EXPECT_NEAR(a.fx, b.fx, 1e-9);
        EXPECT_NEAR(a.cx, b.cx, 1e-9);
        EXPECT_NEAR(a.cy, b.cy, 1e-9);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(a.cameraFromWorldT[c], b.cameraFromWorldT[c], 1e-9);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(a.cameraFromWorldR[c][k], b.cameraFromWorldR[c][k], 1e-9);
        }
        ASSERT_EQ(imported.scene.lights.size(), room.scene.lights.size());
        EXPECT_EQ(imported.nominalRadiance, room.nominalRadiance);
        EXPECT_EQ(imported.photos.at(0).lightsOn, room.photos.at(0).lightsOn);
        EXPECT_EQ(imported.photos.at(0).file, dir.path() / "out" / "room.exr");
        EXPECT_TRUE(imported.objectSettings.at("table").removable);
        EXPECT_EQ(imported.averageReflectance, 0.6);
        EXPECT_EQ(imported.scene.polygons.size(), room.scene.polygons.size());
    }
}

/// The message of the error `f` throws, of type E ("" when none).
template <typename E, typename F>
std::string errorOf(F f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "";
}

/// Whether <dir>/out is as it was: absent, or holding only `keep`.
bool outputUntouched(const TempDir& dir, const std::string& keep = "") {
    const fs::path out = dir.path() / "out";
    if (!fs::exists(out)) return keep.empty();
    int n = 0;
    for (const auto& entry : fs::directory_iterator(out))
        n += entry.path().filename() == keep ? 1 : 100;
    return n == 1;
}

TEST(ColmapImport, BadInputsNameTheirFileAndWriteNothing) {
    TempDir dir("colmap_import");
    relight::ColmapImportOptions o = roomModel(dir, false);
    using relight::InputError;

    auto missing = o;
    missing.image = "room.exr";
    EXPECT_NE(
        errorOf<InputError>([&] {
            relight::importColmap(missing);
        }).find("images.txt: no image named \"room.exr\" (it has 1 image: \"shots/room.exr\")"),
        std::string::npos);

    // A mesh that does not load.
    auto badMesh = o;
    badMesh.mesh = dir.write("bad.obj", "v 0 0 0\nf 1 2 3\n");
    std::string e = errorOf<InputError>([&] { relight::importColmap(badMesh); });
    EXPECT_NE(e.find("bad.obj:2:"), std::string::npos) << e;

    // A light with a negative radiance: the lights file and the key.
    auto badLights = o;
    badLights.lights =
        dir.write("lights.json",
                  R"([{"name": "L", "type": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]],
             "radiance": [1, -1, 1]}])");
    e = errorOf<InputError>([&] { relight::importColmap(badLights); });
    EXPECT_NE(e.find("lights.json: key \"[0].radiance[1]\": radiance must not be negative"),
              std::string::npos)
        << e;

    // An object the mesh does not have.
    auto badObjects = o;
    badObjects.objects = dir.write("objects.json", R"({"sofa": {"removable": true}})");
    e = errorOf<InputError>([&] { relight::importColmap(badObjects); });
    EXPECT_NE(e.find("objects.json: key \"sofa\": no object of this name in the mesh"),
              std::string::npos)
        << e;
    auto badOn = o;
    badOn.lightsOn = std::vector<std::string>{"A", "Q"};
    e = errorOf<InputError>([&] { relight::importColmap(badOn); });
    EXPECT_NE(e.find("--lights-on: no light named \"Q\""), std::string::npos) << e;
    EXPECT_TRUE(outputUntouched(dir));

    // A folder that is not empty is left alone unless forced.
    fs::create_directories(dir.path() / "out");
    dir.write("out/notes.txt", "mine");
    e = errorOf<relight::OutputError>([&] { relight::importColmap(o); });
    EXPECT_NE(e.find("the folder is not empty (--force writes into it)"), std::string::npos) << e;
    EXPECT_TRUE(outputUntouched(dir, "notes.txt"));
    o.force = true;
    relight::importColmap(o);
    EXPECT_TRUE(fs::exists(dir.path() / "out" / "scene.json"));
}

TEST(ColmapImport, PhotoOfAnotherSizeThanItsCamera) {
    TempDir dir("colmap_import");
    const relight::ColmapImportOptions o = roomModel(dir, false);
    dir.write("sparse/cameras.txt", "# c\n1 PINHOLE 160 240 170 170 160 120\n");
    const std::string e = errorOf<relight::InputError>([&] { relight::importColmap(o); });
    EXPECT_NE(e.find("shots/room.exr: photo is 320x240 but its camera ("), std::string::npos) << e;
    EXPECT_NE(e.find("cameras.txt:2) is 160x240"), std::string::npos) << e;
    EXPECT_TRUE(outputUntouched(dir));
}

// A photo through a SIMPLE_RADIAL camera is undistorted into a linear EXR beside scene.json,
// and the scene's camera is the fitted pinhole's, with the principal point moved by half a
// pixel.
TEST(ColmapImport, DistortedPhotoIsUndistorted) {
    TempDir dir("colmap_import");
    relight::ColmapImportOptions o = roomModel(dir, false);
    const relight::SceneFile room = relight::loadScene(fs::path(RELIGHT_DATA_DIR) / "room");
    colmap::Model model;
    model.cameras[1] = {1, "SIMPLE_RADIAL", 320, 240, {170, 160, 120, -0.05}, ""};
    model.images.push_back(colmap::colmapImage(room.camera, 5, 1, "shots/room.exr"));
    colmap::writeText(dir.path() / "sparse", model);
    const relight::ColmapImportResult r = relight::importColmap(o);
    EXPECT_TRUE(r.undistorted);
    EXPECT_LT(r.focalScale, 1);  // barrel
    const relight::SceneFile imported = relight::loadScene(dir.path() / "out");
    EXPECT_EQ(imported.photos.at(0).file, dir.path() / "out" / "room.undistorted.exr");
    EXPECT_EQ(imported.photos.at(0).encoding, relight::PhotoSpec::Encoding::linear);
    EXPECT_NEAR(imported.camera.fx, 170 * r.focalScale, 1e-9);
    EXPECT_NEAR(imported.camera.cx, 159.5, 1e-12);
    const relight::Image photo = relight::readImage(imported.photos.at(0).file);
    EXPECT_EQ(photo.width, 320);
    EXPECT_EQ(photo.height, 240);
}

}  // namespace
