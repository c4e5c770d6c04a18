// The stress-room scene package (tests/support/stress_room.h, writeStressRoomPackage) read
// back by relight::loadScene: the same scene bit for bit (cut where a surface stands across
// another, as the loader cuts, and the faces inside solids left out), no repairs, a camera
// that sees the room.
#include <gtest/gtest.h>

#include <cstring>

#include "radiosity/buried.h"
#include "radiosity/contact_split.h"
#include "relight/io/scene_file.h"
#include "temp_dir.h"
#include "tests/support/stress_room.h"

namespace {

using radiosity::Polygon;
using radiosity::Rgb;
using radiosity::Vec3;

bool sameBits(const Vec3& a, const Vec3& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
bool sameBits(const Rgb& a, const Rgb& b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

void checkRoundTrip(const stress::StressRoomOptions& o) {
    const stress::StressRoom room = stress::makeStressRoom(o);
    relight::test::TempDir dir("stress_room_package");
    stress::writeStressRoomPackage(room, dir.path());
    const relight::SceneFile sf = relight::loadScene(dir.path());
    EXPECT_TRUE(sf.warnings.empty()) << sf.warnings.front();
    // The generator's scene cut as the loader cuts it (radiosity/contact_split.h): the
    // geometry first, the lights' faces after it.
    radiosity::Scene a = room.scene;
    size_t geometry = 0;
    while (geometry < a.polygons.size() && a.polygons[geometry].light < 0) ++geometry;
    const std::vector<Polygon> lightFaces(a.polygons.begin() + static_cast<long>(geometry),
                                          a.polygons.end());
    a.polygons.resize(geometry);
    const radiosity::ContactSplitReport cut = radiosity::splitAtContacts(a.polygons, geometry);
    EXPECT_EQ(cut.piecesAdded, sf.contactSplit.piecesAdded);
    for (radiosity::Light& l : a.lights)
        for (int& p : l.polygons) p += cut.piecesAdded;
    a.polygons.insert(a.polygons.end(), lightFaces.begin(), lightFaces.end());
    // Then the faces inside closed solids left out, as the loader leaves them out (nothing
    // in the package is removable).
    {
        radiosity::BuriedContext context;
        context.eye = sf.camera.position();
        const radiosity::Visibility vis(a);
        const std::vector<int> buried =
            radiosity::findBuriedPolygons(a, a.polygons.size() - lightFaces.size(), vis, context);
        EXPECT_EQ(static_cast<int>(buried.size()), sf.buriedPolygons);
        radiosity::removeBuriedPolygons(a, buried);
    }
    const radiosity::Scene& b = sf.scene;
    ASSERT_EQ(a.objects, b.objects);
    ASSERT_EQ(a.polygons.size(), b.polygons.size());
    for (size_t i = 0; i < a.polygons.size(); ++i) {
        const Polygon& p = a.polygons[i];
        const Polygon& q = b.polygons[i];
        ASSERT_EQ(p.vertexCount, q.vertexCount) << i;
        for (int k = 0; k < p.vertexCount; ++k) ASSERT_TRUE(sameBits(p.v[k], q.v[k])) << i;
        ASSERT_EQ(p.object, q.object) << i;
        ASSERT_EQ(p.light, q.light) << i;
        ASSERT_TRUE(sameBits(p.rho, q.rho)) << i;
    }
    ASSERT_EQ(a.lights.size(), b.lights.size());
    for (size_t i = 0; i < a.lights.size(); ++i) {
        EXPECT_EQ(a.lights[i].name, b.lights[i].name);
        EXPECT_EQ(a.lights[i].polygons, b.lights[i].polygons);
        EXPECT_TRUE(sameBits(a.lights[i].radiance, b.lights[i].radiance));
    }
    // The camera is in the room's air, and the floor's far corner region is in view.
    const Vec3 eye = room.toLocal(sf.camera.position());
    for (int k = 0; k < 3; ++k) {
        EXPECT_GT(eye[k], 0.0);
        EXPECT_LT(eye[k], room.size[k]);
    }
    double u = 0, v = 0, depth = 0;
    const Vec3 target = room.toWorld({0.8 * room.size.x, 0.8 * room.size.y, 0.2 * room.size.z});
    ASSERT_TRUE(sf.camera.project(target, u, v, depth));
    EXPECT_NEAR(u, sf.camera.cx, 1e-6);
    EXPECT_NEAR(v, sf.camera.cy, 1e-6);
}

}  // namespace

TEST(StressRoomPackage, QuadsLoadBackBitForBit) {
    stress::StressRoomOptions o;
    o.seed = 7;
    checkRoundTrip(o);
}

TEST(StressRoomPackage, RotatedJitteredTrianglesFarFromTheOriginLoadBackBitForBit) {
    stress::StressRoomOptions o;
    o.seed = 8;
    o.triangles = true;
    o.grid = 3;
    o.jitter = 0.002;
    o.rotate = true;
    o.offset = 5;
    o.scale = 0.01;
    checkRoundTrip(o);
}
