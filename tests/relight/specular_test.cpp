// The specular pass (relight/dynamic/specular.h; ../shared/seeds/000, §6): each light's
// glossy sum against its closed form (radiosity/emitter.h, unitGlossy), the Blinn-Phong
// term of a point lamp over a plane at the mirror point and off it, in the relit image of
// the room, and the edit key's checks.
#include "relight/dynamic/specular.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "radiosity/detail/rng.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/dynamic/overlay_samples.h"
#include "relight/errors.h"
#include "relight/io/edit_writer.h"
#include "room_fixture.h"
#include "temp_dir.h"

using namespace relight;
using radiosity::Vec3;

namespace {

constexpr double kPi = std::numbers::pi;

/// A 4 m x 4 m floor (z = 0, facing up).
radiosity::Scene floorScene() {
    radiosity::Scene s;
    s.objects = {"floor"};
    s.polygons.push_back(radiosity::makePolygon({{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}}, 0,
                                                Rgb::gray(0.5)));
    return s;
}

/// The closed form, written out here rather than through blinnPhongLobe: the radiance a
/// Blinn-Phong surface (normal n) at x sends towards `eye` from a point lamp of intensity I
/// at `lamp`: ks (s + 8) / (8 pi) (n.h)^s I cos / d^2.
double pointLampSpecular(const Vec3& x, const Vec3& n, const Vec3& eye, const Vec3& lamp, double I,
                         double ks, double s) {
    const Vec3 l = glm::normalize(lamp - x), v = glm::normalize(eye - x);
    const Vec3 h = glm::normalize(l + v);
    const double d2 = glm::dot(lamp - x, lamp - x);
    return ks * (s + 8) / (8 * kPi) * std::pow(glm::dot(n, h), s) * I * glm::dot(n, l) / d2;
}

}  // namespace

TEST(Specular, APointLampOverAPlanePeaksAtTheMirrorPoint) {
    const radiosity::Visibility vis(floorScene());
    const Vec3 lamp{0.2, -0.1, 1.5}, eye{-1.0, 0.6, 2.0};
    const double I = 3.0, ks = 0.6, s = 100;
    radiosity::Scene scene = floorScene();
    radiosity::Light P;
    P.name = "P";
    P.radiance = Rgb::gray(I);
    P.emitter = radiosity::makePointLamp("P", lamp, Rgb::gray(1));
    scene.lights.push_back(P);
    const SpecularLights lights(scene, std::vector<Rgb>{Rgb::gray(I)});
    const Specular spec{Rgb{ks, ks / 2, 0}, s};
    // The mirror point: where the line from the eye to the lamp's mirror image (z -> -z)
    // meets the floor. There h = n, and the lobe's peak is ks (s + 8) / (8 pi) I cos / d^2.
    const Vec3 mirrorLamp{lamp.x, lamp.y, -lamp.z};
    const double t = eye.z / (eye.z - mirrorLamp.z);
    const Vec3 m = eye + t * (mirrorLamp - eye);
    const Vec3 n{0, 0, 1};
    const Rgb peak = lights.radiance(spec, vis, {m, n, 0}, glm::normalize(eye - m), 16, 7);
    const double d2 = glm::dot(lamp - m, lamp - m);
    const double closed = ks * (s + 8) / (8 * kPi) * I * (lamp.z / std::sqrt(d2)) / d2;
    // One shadow ray and a closed form: only rounding separates them.
    EXPECT_NEAR(peak.r, closed, 1e-12 * closed);
    EXPECT_NEAR(peak.g, closed / 2, 1e-12 * closed);
    EXPECT_EQ(peak.b, 0.0);
    // Off the peak, 5, 20 and 40 cm away: as the closed form says; the lobe has fallen well
    // below its peak 20 cm away (5 cm away the nearer lamp outweighs its fall).
    for (const Vec3& off : {Vec3{0.05, 0, 0}, Vec3{0, 0.2, 0}, Vec3{-0.4, 0, 0}}) {
        const Vec3 x = m + off;
        const Rgb L = lights.radiance(spec, vis, {x, n, 0}, glm::normalize(eye - x), 16, 7);
        const double want = pointLampSpecular(x, n, eye, lamp, I, ks, s);
        EXPECT_NEAR(L.r, want, 1e-12 * closed);
        if (glm::length(off) > 0.1) {
            EXPECT_LT(L.r, 0.5 * peak.r);
        }
    }
    // Below the lamp's horizon (the lamp under the floor) and behind the surface: nothing.
    EXPECT_EQ(lights.radiance(spec, vis, {m, -n, 0}, glm::normalize(eye - m), 16, 7).r, 0.0);
}

TEST(Specular, WithAFlatLobeEveryLightGivesItsIrradiance) {
    // lobe = 1 turns unitGlossy into an estimate of unitIrradiance: the same draws for a
    // sun and a sky (equal to rounding), and points of the face against the exact contour
    // integral for a quad lamp.
    const radiosity::Visibility vis(floorScene());
    const radiosity::ReceiverPoint p{{0.1, 0.2, 0}, {0, 0, 1}, 0};
    const radiosity::Emitter::Lobe one = [](const Vec3&) { return 1.0; };
    const auto sun = radiosity::makeSun("S", {0.3, 0.2, 1}, 5.0, Rgb::gray(1));
    radiosity::Sh9Rgb sky;
    sky.c[0] = Rgb::gray(1);
    sky.c[2] = Rgb::gray(0.4);
    const auto env = radiosity::makeEnvironment("E", sky);
    for (const radiosity::Emitter* e : {sun.get(), env.get()}) {
        double a[9] = {}, b[9] = {};
        radiosity::Rng r1(5), r2(5);
        e->unitIrradiance(vis, p, 64, r1, a);
        e->unitGlossy(vis, p, one, 64, r2, b);
        for (int c = 0; c < e->components(); ++c) EXPECT_NEAR(a[c], b[c], 1e-12) << e->type();
    }
    // A rectangle and a trapezoid (the bilinear map's area changes across it), 0.6 m above.
    for (const auto& face :
         {std::vector<Vec3>{{-0.3, -0.2, 0.6}, {-0.3, 0.4, 0.6}, {0.5, 0.4, 0.6}, {0.5, -0.2, 0.6}},
          std::vector<Vec3>{
              {-0.3, -0.2, 0.6}, {-0.1, 0.4, 0.6}, {0.3, 0.4, 0.6}, {0.5, -0.2, 0.6}}}) {
        const auto quad = radiosity::makeQuadLamp("Q", {face}, {}, Rgb::gray(1));
        double exact = 0, glossy = 0;
        quad->unitUnoccluded(p, &exact);
        radiosity::Rng rng(3);
        quad->unitGlossy(vis, p, one, 1024, rng, &glossy);
        // 32 x 32 stratified points of an integrand that varies smoothly over the face:
        // the estimate's error is far below 0.5 % (measured: 4.9e-5 and 1.1e-4).
        EXPECT_NEAR(glossy, exact, 5e-3 * exact);
    }
}

namespace {

/// The room prepared once, changeable (sessions insert into its solver).
Relighting& room() {
    static const auto r = [] {
        RelightOptions o = test::coarseOptions();
        o.pixelLight = true;
        return prepareRelighting(loadScene(RELIGHT_DATA_DIR "/room"), o);
    }();
    return *r;
}

}  // namespace

TEST(Specular, TheRelitImageAddsTheLobeAtTheMirrorPixelAndOffIt) {
    Relighting& r = room();
    const Camera& cam = r.scene.camera;
    // A black plane 1 cm over the floor (clear of the table and the cabinet), a point lamp
    // above it, the room's lamps off: a pixel wholly on the plane shows the lamp's specular
    // term alone (its diffuse is 0). The lamp is placed on the mirror ray of the eye through
    // the plane's point m: m is the mirror point, h = n there.
    const double zp = 0.01, I = 2.0, ks = 0.8, s = 20;
    const double x0 = 1.5, x1 = 2.5, y0 = 0.8, y1 = 1.8;
    VirtualObject plane;
    plane.name = "plane";
    plane.reflectance = Rgb{};
    plane.polygons = {
        radiosity::makePolygon({{x0, y0, zp}, {x1, y0, zp}, {x1, y1, zp}, {x0, y1, zp}}, 0, Rgb{})};
    plane.specular = Specular{Rgb::gray(ks), s};
    const Vec3 eye = cam.position();
    const Vec3 m{2.0, 1.3, zp};
    const Vec3 in = glm::normalize(m - eye);
    const Vec3 out{in.x, in.y, -in.z};
    const Vec3 lamp = m + ((1.2 - zp) / out.z) * out;
    VirtualLight P{"P", {}, Rgb{}, radiosity::makePointLamp("P", lamp, Rgb::gray(I))};
    const std::vector<Rgb> off(r.scene.scene.lights.size());
    // One session, the term set and taken off again: the comparison is of the term alone.
    DynamicRelighting dyn(r, off);
    dyn.addLight(P);
    dyn.addObject(plane);
    const Image withSpec = dyn.render(DisplayMode::pixel);
    ASSERT_EQ(dyn.setObjectSpecular("plane", std::nullopt), 1);
    const Image without = dyn.render(DisplayMode::pixel);
    double u = 0, v = 0, depth = 0;
    ASSERT_TRUE(cam.project(m, u, v, depth));
    const int mx = static_cast<int>(std::lround(u)), my = static_cast<int>(std::lround(v));
    ASSERT_TRUE(mx >= 25 && mx + 8 < cam.width && my >= 0 && my < cam.height) << u << " " << v;
    // The pixel's value: the mean of the closed form over the overlay's samples
    // (overlay_samples.h), each a camera ray meeting the plane.
    const OverlaySamples samples(r.items.spp);
    auto expected = [&](int x, int y) {
        double sum = 0;
        for (int k = 0; k < samples.count(); ++k) {
            const auto [su, sv] = samples.at(x, y, k);
            const Vec3 d = cam.rayDirection(su, sv);
            const Vec3 x3 = eye + ((zp - eye.z) / d.z) * d;
            sum += pointLampSpecular(x3, {0, 0, 1}, eye, lamp, I, ks, s);
        }
        return sum / samples.count();
    };
    const double d = glm::length(lamp - m);
    const double peak = ks * (s + 8) / (8 * kPi) * I * ((lamp.z - zp) / d) / (d * d);
    const double atMirror = expected(mx, my);
    // The mirror pixel is at the lobe's peak: within the lobe's fall over half a pixel.
    EXPECT_NEAR(atMirror, peak, 0.05 * peak);
    // Float rounding of the image (2^-24 relative) and of the plane's depth: 1e-5.
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(withSpec.at(mx, my)[c], atMirror, 1e-5 * peak) << c;
    // Off the peak: 8 and 25 pixels to the side (the lobe at s = 20 is broad: 25 pixels
    // away it has fallen by a third).
    for (int dx : {8, -25}) {
        const double want = expected(mx + dx, my);
        if (dx < -20) {
            EXPECT_LT(want, 0.7 * atMirror) << dx;
        }
        EXPECT_NEAR(withSpec.at(mx + dx, my)[0], want, 1e-5 * peak) << dx;
    }

    // Without the key the plane is black (its reflectance is 0), and nothing else changes:
    // every pixel off the plane is the same bit for bit.
    EXPECT_EQ(without.at(mx, my)[0], 0.0f);
    size_t changed = 0, elsewhere = 0;
    for (int y = 0; y < without.height; ++y)
        for (int x = 0; x < without.width; ++x) {
            const Vec3 ray = cam.rayDirection(x, y);
            const Vec3 x3 = eye + ((zp - eye.z) / ray.z) * ray;
            // The plane's pixels, with a margin of a pixel's footprint (< 2 cm here).
            const bool onPlane =
                x3.x > x0 - 0.05 && x3.x < x1 + 0.05 && x3.y > y0 - 0.05 && x3.y < y1 + 0.05;
            for (int c = 0; c < 3; ++c)
                if (withSpec.at(x, y)[c] != without.at(x, y)[c]) ++(onPlane ? changed : elsewhere);
        }
    EXPECT_GT(changed, 100u);
    EXPECT_EQ(elsewhere, 0u);
}

TEST(Specular, TheEditKeyIsCheckedAndWrittenBack) {
    const SceneFile& sf = test::coarseRoom().scene;
    test::TempDir dir;
    const std::string box = RELIGHT_DATA_DIR "/room/objects/box.obj";
    auto editWith = [&](const std::string& specular) {
        return R"({"format": "relight-edit/1", "add_objects": [{"name": "box", "file": ")" + box +
               R"(", "reflectance": [0.5, 0.5, 0.5], "transform": [[1,0,0,1.25],[0,1,0,1.95],)"
               R"([0,0,1,0],[0,0,0,1]])" +
               (specular.empty() ? "" : ", \"specular\": " + specular) + "}]}";
    };
    auto errorOf = [&](const std::string& specular) -> std::string {
        try {
            loadEdit(dir.write("e.json", editWith(specular)), sf);
        } catch (const InputError& e) {
            return e.what();
        }
        ADD_FAILURE() << "no InputError for " << specular;
        return {};
    };
    auto has = [](const std::string& text, const std::string& part) {
        return text.find(part) != std::string::npos;
    };
    EXPECT_TRUE(has(errorOf(R"({"ks": [0.1, -0.2, 0.1], "shininess": 8})"),
                    "add_objects[0].specular.ks[1]"));
    EXPECT_TRUE(has(errorOf(R"({"ks": [0.1, 0.2, 0.1], "shininess": 0})"),
                    "add_objects[0].specular.shininess"));
    EXPECT_TRUE(has(errorOf(R"({"ks": [0.1, 0.2, 0.1], "shininess": -3})"),
                    "add_objects[0].specular.shininess"));
    EXPECT_TRUE(has(errorOf(R"({"ks": "shiny", "shininess": 8})"), "add_objects[0].specular.ks"));
    EXPECT_TRUE(has(errorOf(R"({"ks": [0.1, 0.2, 0.1], "shininess": "high"})"),
                    "add_objects[0].specular.shininess"));
    EXPECT_TRUE(has(errorOf(R"({"ks": [0.1, 0.2, 0.1]})"), "add_objects[0].specular"));
    EXPECT_TRUE(has(errorOf(R"({"ks": [0.1, 0.2, 0.1], "shininess": 8, "gloss": 1})"),
                    "add_objects[0].specular"));
    EXPECT_TRUE(has(errorOf(R"(0.5)"), "add_objects[0].specular"));

    const EditFile none = loadEdit(dir.write("e.json", editWith("")), sf);
    EXPECT_FALSE(none.addObjects.at(0).specular);
    EditFile e =
        loadEdit(dir.write("e.json", editWith(R"({"ks": [0.3, 0.2, 0.1], "shininess": 64})")), sf);
    ASSERT_TRUE(e.addObjects.at(0).specular);
    EXPECT_EQ(e.addObjects[0].specular->ks, Rgb(0.3, 0.2, 0.1));
    EXPECT_EQ(e.addObjects[0].specular->shininess, 64.0);
    // Written and read back: the same term.
    writeEdit(dir.path() / "back.json", e);
    const EditFile back = loadEdit(dir.path() / "back.json", sf);
    ASSERT_TRUE(back.addObjects.at(0).specular);
    EXPECT_EQ(back.addObjects[0].specular->ks, Rgb(0.3, 0.2, 0.1));
    EXPECT_EQ(back.addObjects[0].specular->shininess, 64.0);
    // No key: none written.
    writeEdit(dir.path() / "plain.json", none);
    EXPECT_FALSE(editJson(none, dir.path())["add_objects"][0].contains("specular"));
}
