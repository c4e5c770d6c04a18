// Tests of COLMAP's model files and cameras (relight/io/colmap_model.h, colmap_camera.h):
// each bundled scene's camera written as a COLMAP model, text and binary, and read back;
// projections through COLMAP's own equations against the imported camera's; the lens
// distortion's inverse; and one bad input per kind of error, each naming its file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <string>

#include "relight/io/colmap_camera.h"
#include "relight/io/colmap_model.h"
#include "relight/io/scene_file.h"
#include "temp_dir.h"

namespace {

namespace fs = std::filesystem;
using radiosity::Vec3;
using relight::InputError;
using relight::test::TempDir;
namespace colmap = relight::colmap;

/// The largest difference between two scene cameras' numbers.
double cameraDifference(const relight::Camera& a, const relight::Camera& b) {
    double d = std::max({std::abs(a.fx - b.fx), std::abs(a.fy - b.fy), std::abs(a.cx - b.cx),
                         std::abs(a.cy - b.cy)});
    for (int c = 0; c < 3; ++c) {
        d = std::max(d, std::abs(a.cameraFromWorldT[c] - b.cameraFromWorldT[c]));
        for (int r = 0; r < 3; ++r)
            d = std::max(d, std::abs(a.cameraFromWorldR[c][r] - b.cameraFromWorldR[c][r]));
    }
    return d;
}

/// The message of the InputError `f` throws ("" when it throws none).
template <typename F>
std::string inputError(F f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

// Each bundled scene's camera as a COLMAP model (two images, so that the right one must be
// picked) reads back as the scene's camera to 1e-9 (17 digits in text, the doubles
// themselves in binary: only the quaternion's rounding is left, ~1e-16).
void roundTripBundledScenes(bool binary) {
    for (const char* scene : {"room", "cornell", "room-multi"}) {
        SCOPED_TRACE(scene);
        const relight::Camera original =
            relight::loadScene(fs::path(RELIGHT_DATA_DIR) / scene).camera;
        colmap::Model model;
        model.cameras[3] = colmap::colmapCamera(original, 3);
        relight::Camera other = original;
        other.cameraFromWorldT += Vec3(1, 2, 3);
        model.cameras[7] = colmap::colmapCamera(other, 7);
        model.images.push_back(colmap::colmapImage(other, 1, 7, "other.png"));
        model.images.push_back(colmap::colmapImage(original, 2, 3, "sub dir/photo.png"));
        TempDir dir("colmap_round_trip");
        binary ? colmap::writeBinary(dir.path(), model) : colmap::writeText(dir.path(), model);
        const colmap::Model back = colmap::readModel(dir.path());
        EXPECT_EQ(back.imagesFile.extension(), binary ? ".bin" : ".txt");
        const colmap::Image& image = back.image("sub dir/photo.png");
        const colmap::Camera& camera = back.cameraOf(image);
        EXPECT_EQ(camera.id, 3);
        EXPECT_EQ(camera.model, "PINHOLE");
        const relight::Camera imported = colmap::sceneCamera(image, colmap::lensOf(camera));
        EXPECT_EQ(imported.width, original.width);
        EXPECT_EQ(imported.height, original.height);
        EXPECT_LT(cameraDifference(imported, original), 1e-9);
        // The principal point moved by half a pixel, in COLMAP's file.
        EXPECT_DOUBLE_EQ(camera.params[2], original.cx + 0.5);
    }
}

TEST(ColmapRoundTrip, BundledScenesCamerasReadBackEqualText) {
    roundTripBundledScenes(false);
}

TEST(ColmapRoundTrip, BundledScenesCamerasReadBackEqualBinary) {
    roundTripBundledScenes(true);
}

/// A rotation by quaternion product, v' = q v q* (Hamilton, w first): COLMAP's own
/// definition, independent of any matrix.
Vec3 rotateByQuaternion(const std::array<double, 4>& q, const Vec3& v) {
    const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    // t = q v (v a pure quaternion), then t q*.
    const double tw = -x * v.x - y * v.y - z * v.z;
    const double tx = w * v.x + y * v.z - z * v.y;
    const double ty = w * v.y + z * v.x - x * v.z;
    const double tz = w * v.z + x * v.y - y * v.x;
    return {-tw * x + tx * w - ty * z + tz * y, -tw * y + ty * w - tz * x + tx * z,
            -tw * z + tz * w - tx * y + ty * x};
}

// A point seen through COLMAP's equations (quaternion rotation, then u = f x/z + cx with the
// top-left pixel's centre at 0.5) lands half a pixel further right and down than through the
// imported camera, for every pinhole model.
TEST(ColmapProjection, SamePixelThroughColmapAndTheImportedCamera) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int trial = 0; trial < 200; ++trial) {
        colmap::Image image;
        image.qvec = {unit(rng), unit(rng), unit(rng), unit(rng)};  // not unit: normalised
        image.tvec = {unit(rng), unit(rng), 3 + unit(rng)};
        colmap::Camera camera;
        camera.width = 640;
        camera.height = 480;
        const bool simple = trial % 2 == 0;
        camera.model = simple ? "SIMPLE_PINHOLE" : "PINHOLE";
        const double f = 500 + 100 * unit(rng), fy = 500 + 100 * unit(rng);
        const double cx = 320 + 20 * unit(rng), cy = 240 + 20 * unit(rng);
        camera.params =
            simple ? std::vector<double>{f, cx, cy} : std::vector<double>{f, fy, cx, cy};
        const relight::Camera imported = colmap::sceneCamera(image, colmap::lensOf(camera));
        const Vec3 world(unit(rng), unit(rng), unit(rng));
        const Vec3 xc = rotateByQuaternion(image.qvec, world) +
                        Vec3(image.tvec[0], image.tvec[1], image.tvec[2]);
        const double uColmap = f * xc.x / xc.z + cx, vColmap = (simple ? f : fy) * xc.y / xc.z + cy;
        double u = 0, v = 0, depth = 0;
        ASSERT_TRUE(imported.project(world, u, v, depth));
        EXPECT_NEAR(u + 0.5, uColmap, 1e-9);
        EXPECT_NEAR(v + 0.5, vColmap, 1e-9);
        EXPECT_NEAR(depth, xc.z, 1e-12);
    }
}

// Quaternion -> matrix -> quaternion for rotations near each of Shepperd's four branches,
// and a quarter turn about z that takes x to y (Hamilton's convention, not JPL's).
TEST(ColmapQuaternion, RotationRoundTripAndConvention) {
    const double h = std::sqrt(0.5);
    const glm::dmat3 quarter = colmap::rotationFromQuaternion({h, 0, 0, h}, "test");
    const Vec3 y = quarter * Vec3(1, 0, 0);
    EXPECT_NEAR(y.x, 0, 1e-15);
    EXPECT_NEAR(y.y, 1, 1e-15);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> unit(-1, 1);
    const std::array<std::array<double, 4>, 4> axes{
        {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    for (int trial = 0; trial < 400; ++trial) {
        std::array<double, 4> q = axes[static_cast<size_t>(trial % 4)];
        for (double& c : q) c += 0.3 * unit(rng);
        const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        const double sign = q[0] < 0 ? -1 : 1;
        for (double& c : q) c *= sign / n;
        const std::array<double, 4> back =
            colmap::quaternionFromRotation(colmap::rotationFromQuaternion(q, "test"));
        for (int k = 0; k < 4; ++k)
            EXPECT_NEAR(back[static_cast<size_t>(k)], q[static_cast<size_t>(k)], 1e-14);
    }
    EXPECT_NE(inputError([] {
                  colmap::rotationFromQuaternion({0, 0, 0, 0}, "images.txt:5");
              }).find("images.txt:5: the quaternion QVEC is zero"),
              std::string::npos);
}

// Newton's inverse of the OPENCV distortion: distort(undistort(p)) = p across the photo.
TEST(ColmapLens, UndistortInvertsDistort) {
    colmap::Lens lens;
    lens.k1 = -0.2;
    lens.k2 = 0.05;
    lens.p1 = 0.001;
    lens.p2 = -0.002;
    for (double xd = -0.7; xd <= 0.7; xd += 0.05)
        for (double yd = -0.5; yd <= 0.5; yd += 0.05) {
            double x = 0, y = 0, xr = 0, yr = 0;
            ASSERT_TRUE(lens.undistort(xd, yd, x, y)) << xd << " " << yd;
            lens.distort(x, y, xr, yr);
            EXPECT_NEAR(xr, xd, 1e-13);
            EXPECT_NEAR(yr, yd, 1e-13);
        }
    // Beyond the fold of a strong barrel (1 + 3 k1 r^2 = 0 at r = 1 for k1 = -1/3) there is
    // no inverse.
    colmap::Lens fold;
    fold.k1 = -1.0 / 3;
    double x = 0, y = 0;
    EXPECT_FALSE(fold.undistort(0.9, 0.0, x, y));
}

// ---- bad input: each names the file and the line (or record) ----------------------------

void writeModel(const TempDir& dir, const std::string& cameras, const std::string& images) {
    dir.write("cameras.txt", cameras);
    dir.write("images.txt", images);
}

const char* kCameras = "# comment\n1 PINHOLE 320 240 170 170 160 120\n";
const char* kImages =
    "# Image list\n1 1 0 0 0 0 0 3 1 a.png\n\n2 1 0 0 0 0 0 3 1 b.png\n1.0 2.0 -1\n";

TEST(ColmapModelErrors, ReadsTheTextFormWithEmptyAndFullPointLines) {
    TempDir dir("colmap_errors");
    writeModel(dir, kCameras, kImages);
    const colmap::Model m = colmap::readModel(dir.path());
    ASSERT_EQ(m.images.size(), 2u);
    EXPECT_EQ(m.image("b.png").id, 2);
    EXPECT_EQ(m.cameraOf(m.image("b.png")).params[2], 160);
}

TEST(ColmapModelErrors, MissingImageNamesTheFileAndSomeNames) {
    TempDir dir("colmap_errors");
    writeModel(dir, kCameras, kImages);
    const colmap::Model m = colmap::readModel(dir.path());
    const std::string e = inputError([&] { m.image("c.png"); });
    EXPECT_NE(
        e.find("images.txt: no image named \"c.png\" (it has 2 images: \"a.png\", \"b.png\")"),
        std::string::npos)
        << e;
}

TEST(ColmapModelErrors, UndefinedCameraNamesTheImageLine) {
    TempDir dir("colmap_errors");
    writeModel(dir, kCameras, "# x\n\n1 1 0 0 0 0 0 3 9 a.png\n\n");
    const colmap::Model m = colmap::readModel(dir.path());
    const std::string e = inputError([&] { m.cameraOf(m.image("a.png")); });
    EXPECT_NE(e.find("images.txt:3: image \"a.png\" uses camera 9, which"), std::string::npos) << e;
    EXPECT_NE(e.find("cameras.txt does not define"), std::string::npos) << e;
}

TEST(ColmapModelErrors, BadLinesNameTheirLine) {
    TempDir dir("colmap_errors");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"1 PINHOLE 320 240 170 170 160\n", "cameras.txt:1: missing PARAMS"},
        {"#\n1 PINHOLE 320 x 170 170 160 120\n", "cameras.txt:2: bad HEIGHT \"x\""},
        {"1 PINHOLE 320 240 170 170 160 120 7\n", "cameras.txt:1: PINHOLE has 4 parameters"},
        {"1 FISHEYE 320 240 170 170 160 120\n", "cameras.txt:1: unknown camera model \"FISHEYE\""},
        {"1 PINHOLE 320 240 170 nan 160 120\n", "cameras.txt:1: PARAMS is not finite"},
        {"1 PINHOLE 320 240 1 1 1 1\n1 PINHOLE 320 240 1 1 1 1\n",
         "cameras.txt:2: camera 1 defined twice (first at"},
    };
    for (const auto& [cameras, message] : cases) {
        writeModel(dir, cameras, kImages);
        const std::string e = inputError([&] { colmap::readModel(dir.path()); });
        EXPECT_NE(e.find(message), std::string::npos) << e;
    }
    writeModel(dir, kCameras, "1 1 0 0 0 0 0 3 1\n\n");
    EXPECT_NE(inputError([&] { colmap::readModel(dir.path()); }).find("images.txt:1: missing NAME"),
              std::string::npos);
}

TEST(ColmapModelErrors, UnsupportedModelNamesTheUndistorter) {
    colmap::Camera c;
    c.model = "OPENCV_FISHEYE";
    c.params.assign(8, 1.0);
    c.where = "sparse/cameras.txt:4";
    const std::string e = inputError([&] { colmap::lensOf(c); });
    EXPECT_NE(e.find("sparse/cameras.txt:4: camera model OPENCV_FISHEYE is not supported"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("colmap image_undistorter"), std::string::npos) << e;
}

TEST(ColmapModelErrors, TruncatedBinaryNamesTheRecord) {
    TempDir dir("colmap_errors");
    colmap::Model model;
    relight::Camera cam;
    cam.width = 4;
    cam.height = 3;
    model.cameras[1] = colmap::colmapCamera(cam, 1);
    model.images.push_back(colmap::colmapImage(cam, 1, 1, "a.png"));
    colmap::writeBinary(dir.path(), model);
    fs::resize_file(dir.path() / "cameras.bin", 8 + 4 + 4 + 8 + 8 + 16);  // half the params
    const std::string e = inputError([&] { colmap::readModel(dir.path()); });
    EXPECT_NE(e.find("cameras.bin: camera record 0 (byte 8): the file ends at byte 48"),
              std::string::npos)
        << e;
    // A 2D point count beyond the file.
    colmap::writeBinary(dir.path(), model);
    std::string bytes;
    {
        std::ifstream in(dir.path() / "images.bin", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    bytes[bytes.size() - 8] = 5;  // the last field: the number of 2D points
    dir.write("images.bin", bytes);
    const std::string p = inputError([&] { colmap::readModel(dir.path()); });
    EXPECT_NE(p.find("images.bin: image record 0 (byte 8): its 2D points: 5 entries of 24 bytes"),
              std::string::npos)
        << p;
}

TEST(ColmapModelErrors, FolderWithoutModelPointsToItsNumberedSubfolder) {
    TempDir dir("colmap_errors");
    fs::create_directories(dir.path() / "0");
    std::ofstream(dir.path() / "0" / "cameras.txt") << kCameras;
    std::ofstream(dir.path() / "0" / "images.txt") << kImages;
    const std::string e = inputError([&] { colmap::readModel(dir.path()); });
    EXPECT_NE(e.find("no COLMAP model"), std::string::npos) << e;
    EXPECT_NE(e.find("its subfolder " + (dir.path() / "0").string() + " holds one"),
              std::string::npos)
        << e;
}

}  // namespace
