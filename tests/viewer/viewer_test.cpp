// The viewer's GPU display against the CPU display of `relight render`, under Xvfb with
// Mesa's llvmpipe (tests/CMakeLists.txt runs this program through xvfb-run).
//
// Images are compared as the PNG files both write them: 8-bit sRGB of the linear value
// clipped to [0, 1] (relight/io/image.h). Tolerances, in 8-bit steps:
//  - GPU float vs CPU: 1 step. Both compute the same sums (display map weights times the
//    vertex ratios); the GPU in float, the CPU in double, so values differ by about 1e-6
//    relative, which changes the 8-bit code only where a value lies that close to a rounding
//    boundary: by one step.
//  - multipass 8-bit vs float: n steps for n passes, on the pixels that see no lamp face.
//    Each pass's blend rounds once in the sRGB target (n half steps), the 8-bit texel's half
//    step is scaled by the ratio, at most n (n half steps more), and the float image rounds
//    once when written (half a step): n + 1/2 in all, so at most n whole steps between the
//    codes. Pixels that see a lamp's face are excluded: there the display keeps a signed
//    T_rest that an 8-bit texture cannot hold (relight/display/ratio_display.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <thread>

#include "../relight/temp_dir.h"
#include "radiosity/detail/form_factor.h"
#include "relight/display/debug_views.h"
#include "relight/display/multipass.h"
#include "relight/dynamic/quick_light.h"
#include "relight/errors.h"
#include "relight/io/edit_file.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/pixel_light.h"
#include "relight/relighting.h"
#include "viewer/background_work.h"
#include "viewer/frame.h"
#include "viewer/gl_window.h"
#include "viewer/gpu_display.h"
#include "viewer/mouse_tools.h"
#include "viewer/session.h"

namespace relight::viewer {
namespace {

const std::string kRoom = RELIGHT_DATA_DIR "/room";
const char* kLightEdits[] = {"identity", "back_off", "left_off_right_double",
                             "right_off_left_double", "colours"};

int code8(float v) {
    return static_cast<int>(std::lround(255.0 * srgbEncode(std::clamp(v, 0.0f, 1.0f))));
}

/// Largest difference of the 8-bit codes over the pixels `keep` accepts, and how many
/// pixels differ at all.
template <class Keep>
int maxStepDifference(const Image& a, const Image& b, Keep keep, int* differing = nullptr) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    int worst = 0, count = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (!keep(y * a.width + x)) continue;
            int d = 0;
            for (int c = 0; c < 3; ++c)
                d = std::max(d, std::abs(code8(a.at(x, y)[c]) - code8(b.at(x, y)[c])));
            worst = std::max(worst, d);
            count += d > 0 ? 1 : 0;
        }
    if (differing) *differing = count;
    return worst;
}

const auto kAllPixels = [](int) { return true; };

/// What `relight render` shows for the session: the CPU ratio display of its vertex ratios
/// with the virtual parts' overlay (relight/dynamic/dynamic_relighting.h, render()).
Image cpuDisplay(Session& session) {
    const PreparedImage& P = session.prepared();
    Image img = renderRatio(P.display, P.photo, session.vertexRatios(), session.realRadiance(),
                            P.photoRadiance);
    applyOverlay(img, session.overlay());
    return img;
}

/// The room prepared coarsely (what the sessions' tests compare holds at any setting), with
/// the per-pixel display.
std::unique_ptr<Relighting> preparePerPixelRoom() {
    RelightOptions o;
    o.epsilon = 1e-3;
    o.spp = 4;
    o.reflectanceRounds = 3;
    o.pixelLight = true;
    return prepareRelighting(loadScene(kRoom), o);
}

class ViewerGpu : public ::testing::Test {
  protected:
    static void SetUpTestSuite() {
        // A hidden window: this needs a display (xvfb-run); without one the suite fails
        // with WindowError's message rather than skipping.
        window_ = new GlWindow(64, 64, "viewer_test", false);
        RelightOptions o;  // coarse: what is compared holds at any setting
        o.epsilon = 1e-3;
        o.spp = 4;
        o.reflectanceRounds = 3;
        relighting_ = prepareRelighting(loadScene(kRoom), o).release();
    }
    static void TearDownTestSuite() {
        delete relighting_;
        delete window_;
    }
    static EditFile edit(const std::string& name) {
        return loadEdit(kRoom + "/edits/" + name + ".json", relighting_->scene);
    }

    static GlWindow* window_;
    static Relighting* relighting_;
};
GlWindow* ViewerGpu::window_ = nullptr;
Relighting* ViewerGpu::relighting_ = nullptr;

TEST_F(ViewerGpu, FloatFramebufferMatchesRenderOnEveryLightEdit) {
    const PreparedImage& P = relighting_->prepared;
    GpuRatioDisplay display(P);
    for (const char* name : kLightEdits) {
        SCOPED_TRACE(name);
        Session session(*relighting_, edit(name));
        FrameRenderer frame(session, display);
        frame.render();
        const Image gpu = frame.read();
        const Image cpu =
            renderEdit(P, editRadiance(relighting_->scene, edit(name), P.photoRadiance));
        int differing = 0;
        EXPECT_LE(maxStepDifference(gpu, cpu, kAllPixels, &differing), 1);
        // Rounding-boundary cases only: a handful of pixels, not a systematic offset.
        EXPECT_LT(differing, gpu.width * gpu.height / 100);
    }
}

TEST_F(ViewerGpu, MultipassMatchesFloatAndSkipsPassesBelowOne) {
    const PreparedImage& P = relighting_->prepared;
    const DisplayMap& m = P.display;
    // The 8-bit texture holds [0, 1]: photo pixels brighter than that (a lamp the item
    // buffer does not put there, relight/display/ratio_display.h trustPhotoAtEmitters) are clipped
    // in it, as the paper's texture is; they are excluded with the lamp faces, and counted.
    const auto inRange = [&](int px) {
        const float* t = &P.photo.rgb[static_cast<size_t>(px) * 3];
        return std::max({t[0], t[1], t[2]}) <= 1.0f && m.emitterStart[px] == m.emitterStart[px + 1];
    };
    int excluded = 0;
    for (int px = 0; px < m.width * m.height; ++px) excluded += inRange(px) ? 0 : 1;
    EXPECT_LT(excluded, m.width * m.height / 50);
    GpuRatioDisplay display(P);
    int mostPasses = 0;
    for (const char* name : kLightEdits) {
        SCOPED_TRACE(name);
        Session session(*relighting_, edit(name));
        FrameRenderer frame(session, display);
        frame.framebuffer = Framebuffer::float32;
        frame.render();
        const Image f = frame.read();
        frame.framebuffer = Framebuffer::multipass8;
        const int passes = frame.render().passes;
        const Image mp = frame.read();
        // Loscos et al. 2000, §5.3: n = ceil(max B/D) passes, 1 when no ratio exceeds 1.
        // Over the vertices some pixel shows: the others do not add passes.
        const std::vector<Rgb> ratios = session.vertexRatios();
        float maxRatio = 0;
        for (int v : m.vertex)
            maxRatio = std::max(maxRatio,
                                static_cast<float>(ratios[static_cast<size_t>(v)].maxComponent()));
        EXPECT_EQ(passes, multipassCount(maxRatio));
        if (maxRatio <= 1.0f) {
            EXPECT_EQ(passes, 1);
        }
        mostPasses = std::max(mostPasses, passes);
        EXPECT_LE(maxStepDifference(mp, f, inRange), passes);
    }
    // Doubling a light needs the passes: the test must have exercised them.
    EXPECT_GE(mostPasses, 2);
}

TEST_F(ViewerGpu, VirtualPartsMatchTheCpuDisplay) {
    const PreparedImage& P = relighting_->prepared;
    GpuRatioDisplay display(P);
    Session session(*relighting_, edit("virtual_light_and_box"));
    FrameRenderer frame(session, display);
    frame.render();
    const Image gpu = frame.read();
    ASSERT_FALSE(session.overlay().empty());
    EXPECT_LE(maxStepDifference(gpu, cpuDisplay(session), kAllPixels), 1);
}

/// The frame of a light being moved drawn on the GPU (viewer/gpu_moved_light.h) against the
/// CPU's quick frame of the same state: within 1 % of the pixels per shadow map (`maps`),
/// they may differ by more than two 8-bit steps only at shadow edges, where the shadow map's
/// texels and the CPU's one ray per pixel disagree (a thin line of pixels along each edge).
void expectGpuFrameIs(const Image& gpu, const Image& cpu, const char* what, int k, int maps = 1) {
    int differing = 0;
    const int worst = maxStepDifference(gpu, cpu, kAllPixels, &differing);
    size_t beyond = 0;
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x)
            for (int c = 0; c < 3; ++c)
                beyond += std::abs(code8(gpu.at(x, y)[c]) - code8(cpu.at(x, y)[c])) > 2;
    std::printf(
        "%s %d: GPU frame against the CPU's quick frame: %d pixels differ, %zu values "
        "by more than 2 steps, at most %d\n",
        what, k, differing, beyond, worst);
    EXPECT_LE(beyond, static_cast<size_t>(maps * gpu.width * gpu.height) / 100);
}

void expectGpuFrameIsTheQuickOne(Session& session, FrameRenderer& frame, const char* what, int k) {
    frame.render();
    ASSERT_TRUE(frame.drewOnGpu());
    expectGpuFrameIs(frame.read(), session.relitPerPixel(), what, k);
}

/// The image a moved quad lamp's GPU frame estimates (gpu_moved_light.h), made on the CPU:
/// per pixel, g = pi F(x -> face) times the share of the face's four points
/// (ShadowSource::facePoints) that Embree's rays from the frame's receiver reach, then the
/// frame's terms (evalPixelLightTerms), scale and offset.
Image fourPointFrame(const Relighting& r, const MovedLightFrame& f, int light) {
    const radiosity::ShadowSource& face = f.source;
    const int own = r.solver->scene().lights.at(static_cast<size_t>(light)).polygons.at(0);
    const Vec3 normal = glm::normalize(
        glm::cross(face.corners[1] - face.corners[0], face.corners[2] - face.corners[0]));
    const auto points = face.facePoints();
    Image img;
    img.width = f.terms.width;
    img.height = f.terms.height;
    img.rgb.assign(3 * static_cast<size_t>(img.width) * static_cast<size_t>(img.height), 0.0f);
    for (size_t px = 0; px < img.rgb.size() / 3; ++px) {
        const float* rc = &f.receivers[6 * px];
        const Vec3 x(rc[0], rc[1], rc[2]), n(rc[3], rc[4], rc[5]);
        double g = 0;
        const double F = glm::dot(n, n) > 0 ? radiosity::pointToPolygon(
                                                  x, n, face.corners.data(),
                                                  static_cast<int>(face.corners.size()), normal)
                                            : 0.0;
        if (F > 0) {
            int seen = 0;
            for (const Vec3& y : points)  // off the receiver by 10 um: its own face unknown
                seen += r.solver->visibility().visible(x + 1e-5 * n, y, -1, own) ? 1 : 0;
            g = std::numbers::pi * F * seen / 4.0;
        }
        float out[3] = {0, 0, 0};
        if (f.terms.drawn[px]) evalPixelLightTerms(f.terms, px, static_cast<float>(g), out);
        for (size_t c = 0; c < 3; ++c)
            img.rgb[3 * px + c] = f.scale[3 * px + c] * out[c] + f.offset[3 * px + c];
        // The face itself, over the share of the pixel it covers in front of what it shows.
        const Vec3 shows(f.surface[3 * px], f.surface[3 * px + 1], f.surface[3 * px + 2]);
        const FaceCover cover = faceCoverage(
            f.camera, f.samplesPerSide, static_cast<int>(px % static_cast<size_t>(img.width)),
            static_cast<int>(px / static_cast<size_t>(img.width)),
            glm::length(shows - f.camera.position()), face.corners);
        for (size_t c = 0; c < 3; ++c)
            img.rgb[3 * px + c] =
                static_cast<float>(static_cast<double>(img.rgb[3 * px + c]) * (1 - cover.all) +
                                   f.terms.radiance[c] * cover.front);
    }
    return img;
}

/// A drag in the room at the per-pixel display: the room prepared coarsely, a session of
/// the room's edit `edit` with quick moves, its frame renderer, and the pixel (u, v) of the
/// floor point (2, 1.5, 0) the drags start from.
struct RoomDrag {
    std::unique_ptr<Relighting> r = preparePerPixelRoom();
    GpuRatioDisplay display{r->prepared};
    Session session;
    FrameRenderer frame{session, display};
    double u = 0, v = 0;
    explicit RoomDrag(const std::string& edit)
        : session(*r, loadEdit(kRoom + "/edits/" + edit + ".json", r->scene)) {
        session.setQuickMoves(true);
        frame.perPixel = true;
        double depth = 0;
        EXPECT_TRUE(r->scene.camera.project({2.0, 1.5, 0.0}, u, v, depth));
    }
};

// A virtual quad lamp dragged (Session::moveLightTo): its frames on the GPU, a cube shadow
// map from each of four points of its face and Lambert's form factor per pixel, against the
// same estimate on the CPU with Embree's rays. They differ where a map's texels and a ray
// disagree, at the edges of the four points' shadows.
TEST_F(ViewerGpu, AMovedQuadLampsFramesOnTheGpuAreItsFourPointEstimate) {
    RoomDrag d("virtual_light_only");
    auto& [r, display, session, frame, u, v] = d;
    frame.render();
    EXPECT_FALSE(frame.drewOnGpu());
    int epoch = -1;
    for (int k = 1; k <= 3; ++k) {
        SCOPED_TRACE(k);
        session.moveLightTo("V1", session.pick(u - 12 * k, v - 4 * k, "V1"));
        ASSERT_GE(session.movingLight(), 0);
        if (k > 1) {
            EXPECT_EQ(session.movingEpoch(), epoch);  // one drag: one upload
        }
        epoch = session.movingEpoch();
        frame.render();
        ASSERT_TRUE(frame.drewOnGpu());
        const std::optional<MovedLightFrame> f = session.movedLightFrame();
        ASSERT_TRUE(f.has_value());
        ASSERT_EQ(f->source.kind, radiosity::ShadowSource::Kind::face);
        const Image gpuImg = frame.read(), cpuImg = fourPointFrame(*r, *f, session.movingLight());
        // Four maps, each of texels twice as wide as the point lamp's: four shadows' edges,
        // each twice as wide (seen: 1.4-1.9 % of the values beyond two steps; 0.8-1.0 % with
        // maps of 512 texels a side).
        expectGpuFrameIs(
            gpuImg, cpuImg, "quad lamp moved", k,
            GpuMovedLight::kFacePoints * GpuMovedLight::kCubeSide / GpuMovedLight::kFaceCubeSide);
    }
    EXPECT_TRUE(session.settle());
    frame.render();
    EXPECT_FALSE(frame.drewOnGpu());
}

// The frames of a point lamp being moved, drawn on the GPU (viewer/gpu_moved_light.h): its
// direct light from a cube shadow map at each frame, the rest of the image from the
// session's movedLightFrame, against the CPU's quick frame of the same place (the same
// receiver per pixel, one shadow ray). They differ where the map and the ray disagree: at
// a shadow's edge, by up to two of the map's texels.
TEST_F(ViewerGpu, AMovedPointLampsFramesOnTheGpuAreItsQuickFramesOnTheCpu) {
    RoomDrag d("virtual_box");
    auto& [r, display, session, frame, u, v] = d;
    const std::string lamp = session.addPointLampAt(session.pick(u, v), 0.6);
    EXPECT_LT(session.movingLight(), 0);  // inserted: the exact image
    frame.render();
    EXPECT_FALSE(frame.drewOnGpu());
    int epoch = -1;
    for (int k = 1; k <= 3; ++k) {
        SCOPED_TRACE(k);
        session.movePointLampTo(lamp, session.pick(u - 12 * k, v - 4 * k), 0.6);
        ASSERT_GE(session.movingLight(), 0);
        if (k > 1) {
            EXPECT_EQ(session.movingEpoch(), epoch);  // one drag: one upload
        }
        epoch = session.movingEpoch();
        expectGpuFrameIsTheQuickOne(session, frame, "point lamp moved", k);
    }
    // At rest the exact image, made on the CPU as before.
    EXPECT_TRUE(session.settle());
    EXPECT_LT(session.movingLight(), 0);
    frame.render();
    EXPECT_FALSE(frame.drewOnGpu());
}

// A photo whose moved-light frames do not fit in the GPU's memory (here a limit of 1 MB
// given to the renderer: 160 bytes a pixel and the shadow maps need 40 MB at 320 x 240):
// the frames are the CPU's quick ones, and the renderer says why.
TEST_F(ViewerGpu, AMovedLightsFramesBeyondTheGpusMemoryAreTheCpus) {
    RoomDrag d("virtual_box");
    auto& [r, display, session, frame, u, v] = d;
    frame.gpuMemoryLimit = 1000000;
    const std::string lamp = session.addPointLampAt(session.pick(u, v), 0.6);
    frame.render();
    session.movePointLampTo(lamp, session.pick(u - 12, v - 4), 0.6);
    ASSERT_GE(session.movingLight(), 0);
    frame.render();
    EXPECT_FALSE(frame.drewOnGpu());
    EXPECT_NE(frame.gpuNote().find("drawn on the CPU"), std::string::npos) << frame.gpuNote();
    EXPECT_LE(maxStepDifference(frame.read(), session.relitPerPixel(), kAllPixels), 1);
    // Within the limit, the same drag on the GPU.
    FrameRenderer roomy(session, display);
    roomy.perPixel = true;
    roomy.gpuMemoryLimit =
        GpuMovedLight::bytesNeeded(static_cast<size_t>(r->prepared.photo.width) *
                                   static_cast<size_t>(r->prepared.photo.height));
    session.movePointLampTo(lamp, session.pick(u - 24, v - 8), 0.6);
    roomy.render();
    EXPECT_TRUE(roomy.drewOnGpu());
    EXPECT_TRUE(roomy.gpuNote().empty());
}

// The same for a sun turned (its orthographic shadow map): the courtyard's sun dragged as
// the window's sun tool does.
TEST_F(ViewerGpu, ATurnedSunsFramesOnTheGpuAreItsQuickFramesOnTheCpu) {
    RelightOptions o;
    o.epsilon = 1e-3;
    o.spp = 4;
    o.reflectanceRounds = 3;
    o.pixelLight = true;
    const std::unique_ptr<Relighting> r =
        prepareRelighting(loadScene(RELIGHT_DATA_DIR "/courtyard"), o);
    GpuRatioDisplay display(r->prepared);
    Session session(*r, EditFile{});
    session.setQuickMoves(true);
    FrameRenderer frame(session, display);
    frame.perPixel = true;
    frame.render();
    for (int k = 1; k <= 3; ++k) {
        SCOPED_TRACE(k);
        session.dragSun("sun", 6.0, 2.0);
        ASSERT_GE(session.movingLight(), 0);
        expectGpuFrameIsTheQuickOne(session, frame, "sun turned", k);
    }
}

TEST_F(ViewerGpu, DebugViewBMatchesTheCpuView) {
    const PreparedImage& P = relighting_->prepared;
    GpuRatioDisplay display(P);
    Session session(*relighting_, edit("left_off_right_double"));
    FrameRenderer frame(session, display);
    frame.view = ViewKind::B;
    frame.render();
    const Image gpu = frame.read();
    const DebugViews v = computeDebugViews(*relighting_, session.realRadiance());
    Image cpu = v.B;
    for (float& c : cpu.rgb) c = static_cast<float>(static_cast<double>(c) * v.bdScale);
    EXPECT_LE(maxStepDifference(gpu, cpu, kAllPixels), 1);
}

TEST_F(ViewerGpu, DraggedBoxFollowsThePointer) {
    // The box of the room's edit, dragged 40 pixels to the right over the floor: the centre
    // of its pixels moves right by about that much, and the relit image is the CPU's.
    const PreparedImage& P = relighting_->prepared;
    GpuRatioDisplay display(P);
    Session session(*relighting_, edit("virtual_box"));
    FrameRenderer frame(session, display);
    // Where the box is: the centre of the pixels its samples cover, from the overlay (the
    // share of each pixel's samples that no longer see the room).
    const auto boxCentre = [&]() {
        const VirtualOverlay o = session.overlay();
        double sx = 0, n = 0;
        for (int y = 0; y < o.height; ++y)
            for (int x = 0; x < o.width; ++x) {
                const double cover =
                    1.0 -
                    static_cast<double>(o.rgba[(static_cast<size_t>(y) * o.width + x) * 4 + 3]);
                sx += cover * (o.x0 + x);
                n += cover;
            }
        return n > 20 ? sx / n : -1.0;
    };
    const double before = boxCentre();
    ASSERT_GT(before, 0);
    // Grab the box at its centre pixel.
    Pick grab;
    const int cx = static_cast<int>(std::lround(before));
    for (int y = P.photo.height - 1; y >= 0 && grab.object < 0; --y) grab = session.pick(cx, y);
    ASSERT_EQ(grab.object, 0);
    double u = 0, v = 0, depth = 0;
    relighting_->scene.camera.project(grab.point, u, v, depth);
    session.beginDrag(grab.object, grab);
    for (int k = 1; k <= 40; ++k) EXPECT_TRUE(session.dragTo(u + k, v));
    const double during = boxCentre();
    session.endDrag();
    frame.render();
    const Image after = frame.read();
    EXPECT_NEAR(during - before, 40.0, 12.0);  // perspective: the box's far side moves less
    EXPECT_NEAR(boxCentre(), during, 0.5);
    EXPECT_LE(maxStepDifference(after, cpuDisplay(session), kAllPixels), 1);
}

/// True when every display ratio of the session is finite.
bool finiteRatios(const Session& session) {
    for (const Rgb& v : session.vertexRatios())
        if (!std::isfinite(v.r) || !std::isfinite(v.g) || !std::isfinite(v.b)) return false;
    return true;
}

TEST_F(ViewerGpu, ARadianceThatOverflowsTheDisplayIsUndoneAndNamed) {
    // A radiance typed into a slider (ImGui lets a ctrl-click type any number) whose display
    // ratios do not fit a float: refused naming the light, and the session is as before, on
    // the superposition path (light edits only) and with virtual parts (the solver's path).
    for (const char* name : {"identity", "virtual_light_and_box"}) {
        SCOPED_TRACE(name);
        Session session(*relighting_, edit(name));
        const std::vector<Rgb> before = session.vertexRatios();
        ASSERT_TRUE(finiteRatios(session));
        LightControl& light = session.lights().back();  // a virtual light where there is one
        const Rgb radiance = light.radiance();
        const int generation = session.generation();
        light.intensity = 1e300;
        try {
            session.update();
            ADD_FAILURE() << "a radiance of 1e300 was accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("\"" + light.name + "\""), std::string::npos)
                << e.what();
        }
        EXPECT_EQ(light.radiance(), radiance);
        EXPECT_NE(session.generation(), generation);  // the display follows the undo
        const std::vector<Rgb> after = session.vertexRatios();
        ASSERT_EQ(after.size(), before.size());
        // The same radiances again: bit for bit on the superposition path; with virtual
        // parts the solver is warm-started from a solution converged to a tolerance, so
        // within 1e-6 relative (what is seen here: 6e-8).
        for (size_t v = 0; v < after.size(); ++v)
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(after[v][c], before[v][c], 1e-6 * std::max(1.0, std::abs(before[v][c])))
                    << "vertex " << v;
        // A finite change after the refusal is taken as usual.
        light.intensity = radiance.maxComponent() * 0.5;
        EXPECT_NO_THROW(session.update());
        EXPECT_TRUE(finiteRatios(session));
    }
}

// A real lamp placed by a click (the viewer's "place real lamps"): its centre on the surface
// under the pixel clicked (projecting back to it), the quad facing the camera's side, the
// size asked for; moved by a second click; saved into a copy of the room's scene.json as a
// light whose radiance is estimated from the photo, on in it.
TEST_F(ViewerGpu, RealLampPlacedOnTheSurfaceUnderTheClickAndSaved) {
    Session session(*relighting_, edit("identity"));
    const Camera& camera = relighting_->scene.camera;
    const int i = session.placeLampAt(session.pick(160, 20), 0.3, 0.2);
    const PlacedLamp lamp = session.placedLamps().at(static_cast<size_t>(i));
    EXPECT_EQ(lamp.name, "L1");
    double u = 0, v = 0, depth = 0;
    ASSERT_TRUE(camera.project(lamp.centre, u, v, depth));
    EXPECT_NEAR(u, 160, 1e-6);
    EXPECT_NEAR(v, 20, 1e-6);
    const std::vector<Vec3> q = lamp.corners();
    const Vec3 faceNormal = glm::cross(q[1] - q[0], q[2] - q[0]);
    EXPECT_GT(glm::dot(faceNormal, camera.position() - lamp.centre), 0);  // it lights the room
    EXPECT_NEAR(glm::length(faceNormal), 0.3 * 0.2, 1e-12);
    session.moveLampTo(i, session.pick(60, 120));
    ASSERT_TRUE(camera.project(session.placedLamps()[0].centre, u, v, depth));
    EXPECT_NEAR(u, 60, 1e-6);
    EXPECT_NEAR(v, 120, 1e-6);
    // Without a size: the room's lamps' own.
    const int j = session.placeLampAt(session.pick(100, 100));
    EXPECT_EQ(session.placedLamps()[static_cast<size_t>(j)].name, "L2");
    EXPECT_GT(session.placedLamps()[static_cast<size_t>(j)].width, 0.05);

    namespace fs = std::filesystem;
    const test::TempDir tmp("viewer_lamps");
    const fs::path& dir = tmp.path();
    for (const char* f : {"scene.json", "room.obj", "photo.exr"})
        fs::copy_file(fs::path(kRoom) / f, dir / f);
    session.saveLamps(dir);
    EXPECT_TRUE(session.placedLamps().empty());
    const SceneFile saved = loadScene(dir);
    const size_t n = relighting_->scene.scene.lights.size();
    ASSERT_EQ(saved.scene.lights.size(), n + 2);
    EXPECT_EQ(saved.scene.lights[n].name, "L1");
    EXPECT_TRUE(saved.estimateRadiance[n]);
    EXPECT_TRUE(saved.lightOnInPhoto(n));
}

// The box dragged in the per-pixel display (the window's default; Session::setQuickMoves):
// quick frames while it moves (DynamicRelighting::previewLastObject), which the session
// says, and at rest, the pointer still or the button let go, the image of the edit as
// `relight render` draws it (a session started from the saved edit: it inserts the parts as
// render does).
TEST(ViewerSession, ADraggedBoxsQuickFramesSettleToTheEditsImage) {
    const std::unique_ptr<Relighting> r = preparePerPixelRoom();
    namespace fs = std::filesystem;
    const test::TempDir tmp("viewer_boxdrag");
    const fs::path& dir = tmp.path();
    Image rested, released;
    {
        Session session(*r, loadEdit(kRoom + "/edits/virtual_box.json", r->scene));
        session.setQuickMoves(true);
        const Image before = session.relitPerPixel();
        // Grab the box at the pixel of its centre and drag it 30 pixels right.
        double u = 0, v = 0, depth = 0;
        ASSERT_TRUE(r->scene.camera.project({1.25, 1.95, 0.15}, u, v, depth));
        const Pick grab = session.pick(u, v);
        ASSERT_EQ(grab.object, 0);
        session.beginDrag(grab.object, grab);
        for (int k = 1; k <= 30; ++k) ASSERT_TRUE(session.dragTo(u + k, v));
        EXPECT_TRUE(session.exactPending());
        EXPECT_EQ(session.stage().rfind("drag: direct light only", 0), 0u) << session.stage();
        const Image quick = session.relitPerPixel();
        EXPECT_GT(maxStepDifference(quick, before, kAllPixels), 20);  // the box did move
        // The pointer rests, the button still down: the exact image.
        EXPECT_TRUE(session.settle());
        EXPECT_FALSE(session.exactPending());
        EXPECT_EQ(session.stage(), "exact");
        rested = session.relitPerPixel();
        session.save(dir / "rested.json");
        // The quick frame was near it (linear values; DynamicRelighting's test bounds the
        // difference against the truth: the indirect light as without the box, one camera
        // sample per pixel where the box may shade it). Bounds: 2 % of the values beyond
        // 1/255 (seen: 0.4-0.5 %), none beyond 12/255. The worst is on the box's top face
        // at the edge of a shadow across it (pixel 153, 169): the quick frame, with 16 rays
        // at one point of the pixel, has it lit (0.12; the pixel beside it, 157, 169, in the
        // shadow); the settled image, its direct light interpolated from the box's leaf
        // corners, 0.08 at every epsilon from 1e-4 (0.078-0.083), and at 1e-3 since the
        // oracle weighs an element by its dimmest leaf: 10.5-10.9/255 apart. At 1e-3 weighed
        // by the mean the settled image was 0.12 there too, and the worst 7.1/255 elsewhere.
        size_t beyond = 0;
        double worst = 0;
        for (size_t i = 0; i < quick.rgb.size(); ++i) {
            const double d =
                std::abs(static_cast<double>(quick.rgb[i]) - static_cast<double>(rested.rgb[i]));
            beyond += d > 1.0 / 255 ? 1 : 0;
            worst = std::max(worst, d);
        }
        std::printf(
            "quick frame against the settled one: %zu of %zu values beyond 1/255, at "
            "most %.4f\n",
            beyond, quick.rgb.size(), worst);
        EXPECT_LE(beyond, quick.rgb.size() / 50);
        EXPECT_LE(worst, 12.0 / 255);
        // Moved on, then let go: quick again, then exact.
        ASSERT_TRUE(session.dragTo(u + 40, v));
        EXPECT_TRUE(session.exactPending());
        session.endDrag();
        EXPECT_FALSE(session.exactPending());
        released = session.relitPerPixel();
        session.save(dir / "released.json");
    }
    // What `relight render` draws of the saved edits: a session started from each inserts
    // its parts as render does.
    for (const auto& [name, shown] :
         {std::pair{"rested.json", &rested}, {"released.json", &released}}) {
        Session fresh(*r, loadEdit(dir / name, r->scene));
        EXPECT_EQ(maxStepDifference(*shown, fresh.relitPerPixel(), kAllPixels), 0) << name;
    }
}

TEST(BackgroundWork, RunsOffTheWindowsThreadAndSaysWhenItHasEnded) {
    BackgroundWork work;
    EXPECT_FALSE(work.busy());
    EXPECT_FALSE(work.finish());  // nothing started
    std::atomic<bool> go{false};
    std::thread::id ranOn;
    int result = 0;
    work.start("counting", [&] {
        while (!go.load()) std::this_thread::yield();
        ranOn = std::this_thread::get_id();
        result = 42;
    });
    EXPECT_TRUE(work.busy());
    EXPECT_EQ(work.what(), "counting");
    EXPECT_FALSE(work.finish());  // it waits for `go`: not ended
    EXPECT_THROW(work.start("again", [] {}), std::logic_error);
    go = true;
    // Polled as the window does, once a frame; bounded so that a hang fails, not stalls.
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!work.finish() && std::chrono::steady_clock::now() < until)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_FALSE(work.busy());
    EXPECT_EQ(result, 42);
    EXPECT_NE(ranOn, std::this_thread::get_id());
    // Its exception comes back through finish() (the window shows it), once.
    work.start("failing", [] { throw std::runtime_error("no light there"); });
    EXPECT_THROW(work.wait(), std::runtime_error);
    EXPECT_FALSE(work.busy());
    EXPECT_FALSE(work.finish());
}

TEST(ViewerSession, AnImageMadeExactInTheBackgroundIsTheOneMadeAtOnce) {
    // The window makes a quick image exact on its worker thread (viewer/background_work.h):
    // the session's solver, with TBB inside, runs there. The image must be the same, pixel
    // for pixel, as the same settle on the calling thread.
    const std::unique_ptr<Relighting> r = preparePerPixelRoom();
    Image images[2];
    for (int background = 0; background < 2; ++background) {
        Session session(*r, loadEdit(kRoom + "/edits/virtual_box.json", r->scene));
        session.setQuickMoves(true);
        // A real lamp's slider moved with the box in: the quick path, exact on settle().
        LightControl& lamp = session.lights()[0];
        lamp.setRadiance(lamp.radiance() * 0.4);
        session.update();
        ASSERT_TRUE(session.exactPending());
        ASSERT_TRUE(session.canSettle());
        if (background) {
            BackgroundWork work;
            work.start("making the image exact", [&session] { session.settle(); });
            work.wait();
        } else {
            EXPECT_TRUE(session.settle());
        }
        EXPECT_FALSE(session.exactPending());
        EXPECT_FALSE(session.canSettle());
        images[background] = session.relitPerPixel();
    }
    EXPECT_EQ(maxStepDifference(images[0], images[1], kAllPixels), 0);
    EXPECT_EQ(images[0].rgb, images[1].rgb);
}

// The window runs the panel's slow actions on its worker thread (viewer/app.cpp's later()):
// a virtual lamp's strength, which inserts the parts again, and an object brought back. Each
// must give the same floats as the same action run at once on the calling thread.
TEST(ViewerSession, APanelActionInTheBackgroundIsTheOneMadeAtOnce) {
    const std::unique_ptr<Relighting> r = preparePerPixelRoom();
    Image lamp[2], back[2];
    for (int background = 0; background < 2; ++background) {
        Session session(*r, loadEdit(kRoom + "/edits/virtual_light_only.json", r->scene));
        session.setQuickMoves(true);
        session.removeRealObject("table");
        // The panel's actions, captured by value as the window's are.
        const auto run = [&](const char* what, std::function<void()> action) {
            if (!background) return action();
            BackgroundWork work;
            work.start(what, std::move(action));
            work.wait();
        };
        // The virtual lamp's intensity slider, let go: no quick path (the parts are inserted
        // again), so the frame leaves it to update() and shows what it showed.
        LightControl& v = session.lights().back();
        ASSERT_TRUE(v.isVirtual);
        v.intensity *= 0.5;
        const int generation = session.generation();
        EXPECT_FALSE(session.updateQuickly());
        EXPECT_EQ(session.generation(), generation);
        run("light change", [&session] { session.update(); });
        EXPECT_NE(session.generation(), generation);
        EXPECT_FALSE(session.exactPending());
        lamp[background] = session.relitPerPixel();
        run("bringing the object back",
            [&session, name = std::string("table")] { session.restoreRealObject(name); });
        EXPECT_TRUE(session.removedObjects().empty());
        back[background] = session.relitPerPixel();
    }
    EXPECT_EQ(lamp[0].rgb, lamp[1].rgb);
    EXPECT_EQ(back[0].rgb, back[1].rgb);
    EXPECT_GT(maxStepDifference(lamp[0], back[0], kAllPixels), 0);  // the table came back
}

// A light's slider keeps its quick frames in the window (Session::updateQuickly): with no
// virtual part the superposition, with a box the quick image that settle() makes exact.
TEST(ViewerSession, ASliderIsUpdatedInTheFrameWhereThatIsQuick) {
    const std::unique_ptr<Relighting> r = preparePerPixelRoom();
    Session plain(*r, EditFile{});
    const Image before = plain.relitPerPixel();
    plain.lights()[0].setRadiance(plain.lights()[0].radiance() * 0.4);
    EXPECT_TRUE(plain.updateQuickly());
    EXPECT_FALSE(plain.exactPending());
    EXPECT_GT(maxStepDifference(plain.relitPerPixel(), before, kAllPixels), 0);
    Session boxed(*r, loadEdit(kRoom + "/edits/virtual_box.json", r->scene));
    boxed.lights()[0].setRadiance(boxed.lights()[0].radiance() * 0.4);
    EXPECT_TRUE(boxed.updateQuickly());
    EXPECT_TRUE(boxed.exactPending());
    EXPECT_TRUE(boxed.canSettle());
}

// The mouse tools (viewer/mouse_tools.h) driven as the window drives them, one pointer a
// frame, against the same changes made by calling the session directly: what the tools add
// is the bookkeeping of a drag (where it began, what has been applied, what is left for the
// button's release), and that is what these check, bit for bit.

/// A ToolHost as the window's: act() at once, inBackground() on a worker thread whose end
/// the next frame waits for (the window takes no input meanwhile, viewer/app.cpp).
struct TestHost {
    BackgroundWork work;
    std::vector<std::string> background;  ///< what ran on the worker, in order
    ToolHost host() {
        return {[](const char*, const std::function<void()>& f) {
                    f();  // an exception fails the test
                    return true;
                },
                [this](std::string what, std::function<void()> job) {
                    background.push_back(what);
                    work.start(std::move(what), std::move(job));
                },
                [this] { return work.busy(); }};
    }
    /// One frame: the pointer to the tools, then the worker's end waited for.
    void frame(MouseTools& tools, const PhotoRect& r, double x, double y, bool down) {
        tools.handle(r, Pointer{x, y, down, r.contains(x, y)});
        if (work.busy()) work.wait();
    }
};

/// The photo drawn at twice its size, offset as in a window with a margin.
PhotoRect twiceTheSize(const PreparedImage& p) {
    return PhotoRect{12, 8, 2.0 * p.photo.width, 2.0 * p.photo.height};
}

std::vector<std::vector<double>> emitterValues(Session& s, const std::string& name) {
    for (const LightControl& l : s.lights())
        if (l.name == name && l.emitter) {
            std::vector<std::vector<double>> out;
            for (const radiosity::EmitterField& f : l.emitter->fields()) out.push_back(f.values);
            return out;
        }
    ADD_FAILURE() << "no emitter named " << name;
    return {};
}

Relighting& courtyardPerPixel() {
    static const auto r = [] {
        RelightOptions o;
        o.epsilon = 1e-3;
        o.spp = 4;
        o.reflectanceRounds = 3;
        o.pixelLight = true;
        return prepareRelighting(loadScene(RELIGHT_DATA_DIR "/courtyard"), o);
    }();
    return *r;
}

TEST(MouseTools, ASunDraggedOnThePhotoTurnsAsTheSameDragGivenToTheSession) {
    Relighting& r = courtyardPerPixel();
    const PhotoRect rect = twiceTheSize(r.prepared);
    const double W = r.prepared.photo.width, H = r.prepared.photo.height;
    // The pointer's path: up, pressed, two moves, let go where it last was.
    const double xs[] = {100, 100, 110, 137}, ys[] = {90, 90, 94, 101};
    for (const bool quick : {false, true}) {
        std::vector<std::vector<double>> byMouse, direct;
        std::vector<Rgb> ratiosByMouse, ratiosDirect;
        {
            Session session(r, EditFile{});
            session.setQuickMoves(quick);
            TestHost t;
            MouseTools tools(session, t.host());
            tools.tool = Tool::sun;
            tools.sun = "sun";
            for (int k = 0; k < 4; ++k) t.frame(tools, rect, xs[k], ys[k], k > 0);
            t.frame(tools, rect, xs[3], ys[3], false);
            // The release is solved on the worker, in both displays.
            ASSERT_FALSE(t.background.empty()) << quick;
            EXPECT_EQ(t.background.back(), "turning the sun");
            byMouse = emitterValues(session, "sun");
            ratiosByMouse = session.vertexRatios();
        }
        {
            Session session(r, EditFile{});
            session.setQuickMoves(quick);
            // The drag in photo pixels, summed move by move as a mouse reports it.
            const double du1 = (xs[2] - xs[1]) / rect.w * W, dv1 = (ys[2] - ys[1]) / rect.h * H;
            const double du2 = (xs[3] - xs[2]) / rect.w * W, dv2 = (ys[3] - ys[2]) / rect.h * H;
            if (quick) {  // the sun follows each move; the release makes it exact
                session.dragSun("sun", du1, dv1);
                session.dragSun("sun", du2, dv2);
                session.dragSun("sun", 0, 0);
            } else {  // the whole drag at the release
                session.dragSun("sun", du1 + du2, dv1 + dv2);
            }
            direct = emitterValues(session, "sun");
            ratiosDirect = session.vertexRatios();
        }
        EXPECT_EQ(byMouse, direct) << (quick ? "quick moves" : "ratio display");
        EXPECT_EQ(ratiosByMouse, ratiosDirect);
        Session unturned(r, EditFile{});
        EXPECT_NE(byMouse, emitterValues(unturned, "sun"));  // it did turn
    }
}

TEST(MouseTools, APointLampAddedByAClickGoesWhereItsDragIsLetGo) {
    Relighting& r = courtyardPerPixel();
    const PhotoRect rect = twiceTheSize(r.prepared);
    const auto pixel = [&](double x, double y) {
        double u = 0, v = 0;
        rect.toPixel(x, y, r.prepared.photo.width, r.prepared.photo.height, u, v);
        return std::pair{u, v};
    };
    // A click on the ground, then a drag from elsewhere to a third place.
    const double xa = 150, ya = 380, xb = 200, yb = 390, xc = 260, yc = 400;
    std::vector<std::vector<double>> byMouse, direct;
    std::string name;
    {
        Session session(r, EditFile{});
        TestHost t;
        MouseTools tools(session, t.host());
        tools.tool = Tool::point;
        t.frame(tools, rect, xa, ya, false);
        t.frame(tools, rect, xa, ya, true);  // the click adds the lamp, on the worker
        t.frame(tools, rect, xa, ya, false);
        ASSERT_EQ(tools.tool, Tool::movePoint) << tools.status;
        name = tools.point;
        t.frame(tools, rect, xb, yb, true);
        t.frame(tools, rect, (xb + xc) / 2, (yb + yc) / 2, true);
        t.frame(tools, rect, xc, yc, true);
        t.frame(tools, rect, xc, yc, false);  // let go: the lamp goes there, on the worker
        EXPECT_EQ(t.background,
                  (std::vector<std::string>{"adding a point lamp", "moving the lamp"}));
        byMouse = emitterValues(session, name);
    }
    {
        Session session(r, EditFile{});
        const auto [ua, va] = pixel(xa, ya);
        const Pick a = session.pick(ua, va);
        ASSERT_TRUE(a.hit);
        EXPECT_EQ(session.addPointLampAt(a), name);
        const auto [uc, vc] = pixel(xc, yc);
        const Pick c = session.pick(uc, vc);
        ASSERT_TRUE(c.hit);
        session.movePointLampTo(name, c);
        direct = emitterValues(session, name);
    }
    EXPECT_EQ(byMouse, direct);
}

TEST(MouseTools, ABoxGrabbedAndDraggedIsWhereTheSameDragPutsIt) {
    const std::unique_ptr<Relighting> r = preparePerPixelRoom();
    const PhotoRect rect = twiceTheSize(r->prepared);
    const EditFile edit = loadEdit(kRoom + "/edits/virtual_box.json", r->scene);
    // A window pixel on the box: the first on a scan of the photo at every 4th pixel.
    double x0 = -1, y0 = -1;
    {
        Session probe(*r, edit);
        for (double y = rect.y + 1; y < rect.y + rect.h && x0 < 0; y += 4)
            for (double x = rect.x + 1; x < rect.x + rect.w && x0 < 0; x += 4) {
                double u = 0, v = 0;
                rect.toPixel(x, y, r->prepared.photo.width, r->prepared.photo.height, u, v);
                if (probe.pick(u, v).object == 0) x0 = x, y0 = y;
            }
    }
    ASSERT_GE(x0, 0) << "the box is not in the photo";
    const double path[][2] = {{x0, y0}, {x0 + 6, y0 + 2}, {x0 + 14, y0 + 3}};
    const auto pixel = [&](double x, double y) {
        double u = 0, v = 0;
        rect.toPixel(x, y, r->prepared.photo.width, r->prepared.photo.height, u, v);
        return std::pair{u, v};
    };
    std::vector<Rgb> byMouse, direct;
    {
        Session session(*r, edit);
        TestHost t;
        MouseTools tools(session, t.host());
        t.frame(tools, rect, x0, y0, false);
        for (const auto& p : path) t.frame(tools, rect, p[0], p[1], true);
        EXPECT_EQ(session.dragging(), 0);
        t.frame(tools, rect, path[2][0], path[2][1], false);  // let go, on the worker
        EXPECT_EQ(t.background, std::vector<std::string>{"letting the object go"});
        EXPECT_LT(session.dragging(), 0);
        byMouse = session.vertexRatios();
    }
    {
        Session session(*r, edit);
        const auto [u0, v0] = pixel(x0, y0);
        session.beginDrag(0, session.pick(u0, v0));
        for (int k = 1; k < 3; ++k) {
            const auto [u, v] = pixel(path[k][0], path[k][1]);
            session.dragTo(u, v);
        }
        session.endDrag();
        direct = session.vertexRatios();
    }
    EXPECT_EQ(byMouse, direct);
    Session unmoved(*r, edit);
    EXPECT_NE(byMouse, unmoved.vertexRatios());  // the box did move
}

// A virtual quad lamp dragged with the mouse (Tool::movePoint, Session::moveLightTo): quick
// frames while it moves (its direct light from one ray a pixel, nothing inserted again in
// the frame), then, let go and settled, the image of the lamp inserted where the drag left
// it, as a session that puts it there directly makes it.
TEST(MouseTools, AVirtualLampDraggedIsShownQuicklyThenWhereItWasLetGo) {
    const std::unique_ptr<Relighting> r = preparePerPixelRoom();
    const PhotoRect rect = twiceTheSize(r->prepared);
    const EditFile edit = loadEdit(kRoom + "/edits/virtual_light_only.json", r->scene);
    // Window points over the floor, from world points (the camera's projection).
    const auto window = [&](const Vec3& x) {
        double u = 0, v = 0, depth = 0;
        EXPECT_TRUE(r->scene.camera.project(x, u, v, depth));
        return std::pair{rect.x + (u + 0.5) / r->prepared.photo.width * rect.w,
                         rect.y + (v + 0.5) / r->prepared.photo.height * rect.h};
    };
    const auto path = {window({2.0, 1.5, 0.0}), window({1.8, 1.4, 0.0}), window({1.6, 1.3, 0.0})};
    std::vector<Vec3> byMouse;
    Image settled;
    {
        Session session(*r, edit);
        session.setQuickMoves(true);
        (void)session.relitPerPixel();
        TestHost t;
        MouseTools tools(session, t.host());
        tools.tool = Tool::movePoint;
        tools.point = "V1";
        const std::vector<Vec3> before = session.lights().back().face.corners;
        for (const auto& [x, y] : path) {
            t.frame(tools, rect, x, y, true);
            if (session.lights().back().face.corners != before) {
                EXPECT_TRUE(session.exactPending()) << "a quick frame, not the lamp inserted again";
            }
        }
        EXPECT_TRUE(t.background.empty());
        const Image quick = session.relitPerPixel();
        t.frame(tools, rect, path.end()[-1].first, path.end()[-1].second, false);  // let go
        EXPECT_EQ(t.background, std::vector<std::string>{"moving the lamp"});
        byMouse = session.lights().back().face.corners;
        EXPECT_NE(byMouse, before);
        EXPECT_TRUE(session.settle());
        EXPECT_FALSE(session.exactPending());
        settled = session.relitPerPixel();
        size_t beyond = 0;
        for (size_t i = 0; i < quick.rgb.size(); ++i)
            beyond += std::abs(quick.rgb[i] - settled.rgb[i]) > 4.0f / 255 ? 1 : 0;
        std::printf("quick frame against the settled image: %zu of %zu values beyond 4/255\n",
                    beyond, quick.rgb.size());
    }
    // The same moves given to a session directly (each inserted again), the last one twice
    // as the release repeats it.
    Session session(*r, edit);
    for (size_t k = 0; k <= path.size(); ++k) {
        const auto [x, y] = path.begin()[std::min(k, path.size() - 1)];
        double u = 0, v = 0;
        rect.toPixel(x, y, r->prepared.photo.width, r->prepared.photo.height, u, v);
        session.moveLightTo("V1", session.pick(u, v, "V1"));
    }
    EXPECT_EQ(session.lights().back().face.corners, byMouse);
    const Image direct = session.relitPerPixel();
    ASSERT_EQ(direct.rgb.size(), settled.rgb.size());
    float worst = 0;
    for (size_t i = 0; i < direct.rgb.size(); ++i)
        worst = std::max(worst, std::abs(direct.rgb[i] - settled.rgb[i]));
    EXPECT_EQ(worst, 0.0f);
    // On the floor, facing up, 2 % of its size above it.
    const Vec3 n = glm::cross(byMouse[1] - byMouse[0], byMouse[2] - byMouse[0]);
    EXPECT_GT(n.z, 0.0);
    // (The picked point is Embree's, in float: 1e-6 m at a few metres.)
    for (const Vec3& c : byMouse) EXPECT_NEAR(c.z, 0.02 * 0.35, 1e-6);
}

}  // namespace
}  // namespace relight::viewer
