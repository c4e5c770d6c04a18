// The viewer's frame time under Mesa's llvmpipe (software OpenGL): the work the window does
// per frame (viewer/frame.h), minus the ImGui panel, the present into the window and the
// buffer swap.
//
//   LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 1920x1080x24"
//       ./build/bench/viewer_frames data [--scene NAME] [--upscale K] [--frames N]  (one line)
//
// --context egl: a headless context through EGL on a pbuffer instead of a hidden GLX window
// (viewer/egl_context.h), for a GPU with no X server its driver draws for; no xvfb-run.
//
// --scene courtyard (any scene with a sun): the sun drag alone (sunDrag below).
// VF_DUMP=DIR in the environment: each "at rest" line also writes its two images there
// (`<what>_quick.exr`, `<what>_exact.exr`), to see where they differ.
// Prepares data/room (default RelightOptions), with --upscale K at K times the photo's
// resolution (the camera scaled, the photo upscaled by pixel replication: the same scene,
// K^2 times the pixels and about the same mesh (the refinement reads the photo's samples),
// so the per-pixel parts of a frame can be told from the per-vertex ones). Then, in a hidden
// window, with the session, the GPU display and the frame renderer the viewer uses, N frames of
// each of:
//   - light slider: the first light's intensity moving smoothly from 0.2x to 2x of the
//     photo's and back; without virtual parts a frame is the superposition of the lights'
//     responses per vertex (relight/prepared.h) and the draw;
//   - light slider with a box: the same with a box on the floor; with virtual objects a
//     radiance change is the session's quick path (Session::update: the solver gathers
//     again on the box's links, the direct light recombined from its geometry terms, no
//     shadow ray); after each display's frames the slider rests: the frame that inserts the
//     box again at the radiance reached (Session::settle, `relight render`'s image, its
//     shadow rays from the session's GeometryCache), and how far the last quick image was
//     from it;
//   - box drag: the box dragged over the floor, the pointer moving in equal steps along a
//     straight line of 60 K pixels (about a pixel of the photo per frame at N = 60, as a
//     mouse reports it); the solver moves the last part incrementally (moveLastObject);
//     then, per pixel, the window's quick frames (Session::setQuickMoves: the box's direct
//     light and shadows per pixel, DynamicRelighting::previewLastObject) and the drag at
//     rest (Session::settle: render's image).
//   - point lamp drag and quad lamp insertion (per-pixel display; lampDragAndInsertion).
// each in the ratio display with both framebuffers: float (one pass) and the paper's 8-bit
// multipass (Loscos et al. 2000, §5.3: ratios above 1 drawn as passes added in the
// framebuffer, n = ceil(max ratio), so the draw grows with the brightest ratio), and in the
// per-pixel display (the viewer's default: Session::relitPerPixel on the CPU, shown as an
// image; its "passes" column is 0). A frame is timed from the session's
// change (update() or dragTo) to the end of FrameRenderer::render(), which ends with
// glFinish. Prints the median and 90th percentile of the frame and its parts, in ms.
// The pass count is taken over the vertices some pixel shows: with the box, a floor vertex
// that no pixel shows (D = 0) reaches ratios of 5 to 17 and made the first version of the
// display draw 16-18 passes where the pixels need 2 or 3 (bench/RESULTS.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <unistd.h>

#include "bench/bench_util.h"
#include "radiosity/emitter.h"
#include "radiosity/stopwatch.h"
#include "relight/io/edit_file.h"
#include "relight/io/image.h"
#include "relight/io/scene_file.h"
#include "relight/pipeline/camera.h"
#include "relight/relighting.h"
#include "viewer/egl_context.h"
#include "viewer/frame.h"
#include "viewer/gl_window.h"
#include "viewer/gpu_display.h"
#include "viewer/session.h"

using namespace relight;
using namespace relight::viewer;
using bench::quantile;
using radiosity::Clock;
using radiosity::secondsSince;
namespace fs = std::filesystem;

namespace {

struct Args {
    std::string data;
    std::string scene = "room";
    std::string context = "glx";  ///< "glx": a hidden window; "egl": a pbuffer (no display)
    int upscale = 1, frames = 60;
};

/// `<data_dir> [--upscale K] [--frames N]`; false (after a usage line) when they are wrong.
bool parseArgs(int argc, char** argv, Args& a) {
    const auto usage = [&] {
        std::fprintf(stderr,
                     "usage: %s <data_dir> [--scene NAME] [--upscale K] [--frames N] "
                     "[--context glx|egl]\n",
                     argv[0]);
        return false;
    };
    if (argc < 2) return usage();
    a.data = argv[1];
    for (int i = 2; i < argc; i += 2) {
        if (i + 1 >= argc) return usage();
        if (std::strcmp(argv[i], "--scene") == 0) {
            a.scene = argv[i + 1];
            continue;
        }
        if (std::strcmp(argv[i], "--context") == 0) {
            a.context = argv[i + 1];
            if (a.context != "glx" && a.context != "egl") return usage();
            continue;
        }
        int* value = std::strcmp(argv[i], "--upscale") == 0  ? &a.upscale
                     : std::strcmp(argv[i], "--frames") == 0 ? &a.frames
                                                             : nullptr;
        if (!value) return usage();
        *value = std::atoi(argv[i + 1]);
    }
    if (a.upscale < 1 || a.upscale > 16 || a.frames < 2) {
        std::fprintf(stderr, "%s: --upscale must be in 1..16 and --frames at least 2\n", argv[0]);
        return false;
    }
    return true;
}

/// A folder removed with what is in it when the bench ends, however it ends.
struct TempDir {
    fs::path path;
    explicit TempDir(fs::path p) : path(std::move(p)) { fs::create_directories(path); }
    ~TempDir() {
        std::error_code ec;  // nothing to do about a failure at exit
        fs::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

/// The scene seen at k times the resolution: the camera's focal lengths and size times k,
/// the principal point moved so that each old pixel becomes k x k new ones (pixel centres
/// are integers, so the continuous coordinate u + 1/2 scales by k), and the first photo
/// upscaled by pixel replication, so that every new pixel holds exactly the old one's value.
/// The photo goes to `dir` as linear EXR (an sRGB photo is decoded first).
void upscaleScene(SceneFile& sf, int k, const fs::path& dir) {
    if (sf.photos.empty()) throw InputError(sf.dir.string() + ": the scene has no photo");
    Camera& c = sf.camera;
    const double kd = k;
    c.width *= k;
    c.height *= k;
    c.fx *= kd;
    c.fy *= kd;
    c.cx = (c.cx + 0.5) * kd - 0.5;
    c.cy = (c.cy + 0.5) * kd - 0.5;
    PhotoSpec& photo = sf.photos[0];
    const Image small = readImage(photo.file, photo.encoding == PhotoSpec::Encoding::srgb);
    Image big(small.width * k, small.height * k);
    for (int y = 0; y < big.height; ++y)
        for (int x = 0; x < big.width; ++x) std::copy_n(small.at(x / k, y / k), 3, big.at(x, y));
    photo.file = dir / ("photo_x" + std::to_string(k) + ".exr");
    photo.encoding = PhotoSpec::Encoding::linear;
    writeImage(photo.file, big);
}

/// One scenario's frames: milliseconds per frame and its parts, passes drawn.
struct Samples {
    std::vector<double> frame, update, upload, draw, passes;
};

/// Draws `frames` frames with framebuffer `fb`; frame i is `change(i)` (the session's
/// update or drag) followed by render(). One untimed frame first: the first draw into a
/// target compiles llvmpipe's shader variants for it, which the window pays once.
/// How a frame is drawn: the ratio display on the GPU into one of its framebuffers, or the
/// per-pixel display (relight render's and the viewer's default), drawn on the CPU and shown
/// as an image.
struct Display {
    const char* name;
    bool perPixel;
    Framebuffer framebuffer;
};
constexpr Display kDisplays[] = {{"ratio, float32", false, Framebuffer::float32},
                                 {"ratio, multipass8", false, Framebuffer::multipass8},
                                 {"per-pixel", true, Framebuffer::float32}};

template <class Change>
Samples timeFrames(FrameRenderer& frame, const Display& display, int frames, Change change) {
    frame.framebuffer = display.framebuffer;
    frame.perPixel = display.perPixel;
    frame.render();
    Samples s;
    for (int i = 0; i < frames; ++i) {
        const auto t0 = Clock::now();
        change(i);
        const double update = secondsSince(t0);
        const FrameStats st = frame.render();
        s.frame.push_back(1e3 * secondsSince(t0));
        s.update.push_back(1e3 * update);
        s.upload.push_back(1e3 * st.upload);
        s.draw.push_back(1e3 * st.draw);
        s.passes.push_back(st.passes);
    }
    return s;
}

/// Two runs' samples, one after the other.
Samples concat(Samples a, const Samples& b) {
    a.frame.insert(a.frame.end(), b.frame.begin(), b.frame.end());
    a.update.insert(a.update.end(), b.update.begin(), b.update.end());
    a.upload.insert(a.upload.end(), b.upload.begin(), b.upload.end());
    a.draw.insert(a.draw.end(), b.draw.begin(), b.draw.end());
    a.passes.insert(a.passes.end(), b.passes.begin(), b.passes.end());
    return a;
}

void printHeader() {
    std::printf("%-26s %-18s %-17s %-17s %-17s %-17s %6s %6s\n", "scenario", "display", "frame",
                "update", "upload", "draw", "fps", "passes");
}

void printRow(const char* scenario, const Display& display, const Samples& s) {
    const auto cell = [](const std::vector<double>& v) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%7.2f (%7.2f)", quantile(v, 0.5), quantile(v, 0.9));
        return std::string(buf);
    };
    const auto [lo, hi] = std::minmax_element(s.passes.begin(), s.passes.end());
    char passes[16];
    std::snprintf(passes, sizeof passes, *lo == *hi ? "%.0f" : "%.0f-%.0f", *lo, *hi);
    std::printf("%-26s %-18s %-17s %-17s %-17s %-17s %6.1f %6s\n", scenario, display.name,
                cell(s.frame).c_str(), cell(s.update).c_str(), cell(s.upload).c_str(),
                cell(s.draw).c_str(), 1e3 / quantile(s.frame, 0.5), passes);
}

/// The largest difference of two images of one size, and their rel_rmse-like mean: the
/// root of the mean squared difference over the root of the mean square of `b`.
void compare(const Image& a, const Image& b, double& worst, double& rel) {
    double d2 = 0, b2 = 0;
    worst = 0;
    for (size_t i = 0; i < a.rgb.size() && i < b.rgb.size(); ++i) {
        const double x = a.rgb[i], y = b.rgb[i];
        const double d = x - y;
        worst = std::max(worst, std::abs(d));
        d2 += d * d;
        b2 += y * y;
    }
    rel = b2 > 0 ? std::sqrt(d2 / b2) : 0;
}

/// The pointer or slider resting after quick frames (Session::settle: the exact image):
/// the time of that one frame and how far the last quick image was from it (the GPU's frame
/// where the last one was drawn there), printed.
void printAtRest(Session& session, FrameRenderer& frame, const char* what) {
    const bool gpu = frame.drewOnGpu();
    const Image quick = gpu ? frame.read() : session.relitPerPixel();
    const auto rest = Clock::now();
    session.settle();
    frame.render();
    const double ms = 1e3 * secondsSince(rest);
    const Image exact = session.relitPerPixel();
    double worst = 0, rel = 0;
    compare(quick, exact, worst, rel);
    if (const char* dir = std::getenv("VF_DUMP")) {
        writeImage(std::string(dir) + "/" + what + "_quick.exr", quick);
        writeImage(std::string(dir) + "/" + what + "_exact.exr", exact);
    }
    std::printf(
        "  the %s at rest: the exact image in %.1f ms (one frame); the last quick one%s against "
        "it: at most %.4f, rel_rmse %.5f (per-pixel display)\n",
        what, ms, gpu ? " (GPU)" : "", worst, rel);
}

/// The light slider in every display: light 0 from 0.2x its intensity up to 2x and
/// back (a raised cosine, as a hand moves a slider), then the photo's intensity again.
void lightSlider(const char* scenario, Session& session, FrameRenderer& frame, int frames) {
    LightControl& light = session.lights().at(0);
    const double initial = light.intensity;
    for (const Display& display : kDisplays) {
        const Samples s = timeFrames(frame, display, frames, [&](int i) {
            const double phase = 2 * std::numbers::pi * i / frames;
            light.intensity = initial * (0.2 + 1.8 * 0.5 * (1 - std::cos(phase)));
            session.update();
        });
        printRow(scenario, display, s);
        // With virtual objects the slider's frames are quick images (Session::update); the
        // slider at rest, the exact one (Session::settle): its frame, and how far the last
        // quick image was from it.
        if (session.exactPending()) printAtRest(session, frame, "slider");
    }
    light.intensity = initial;
    session.update();
    session.settle();
    frame.render();
}

/// The sun turned by a drag on the image (Session::dragSun, the viewer's sun tool), in the
/// per-pixel display: frame i is the pointer moved by (1, 0.5) photo pixels (0.56 degrees
/// of azimuth, 0.19 of elevation at 320 x 240) and the image drawn. First each move solved
/// exactly (quick moves off: what the viewer did before, per turn), then the quick frames
/// (Session::setQuickMoves: the sun's direct light per pixel from one ray), the drag
/// resting (Session::settle: the exact image) and how far the last quick image was from it.
/// How a drag of a sun or point lamp is shown: each move solved as `relight render` solves
/// it; the quick frames with the light's direct light per pixel on the CPU (one shadow ray
/// a pixel); the same frames on the GPU from the light's shadow map (gpu_moved_light.h).
struct Variant {
    const char* name;
    bool quick, gpu;
};
constexpr Variant kDragVariants[] = {
    {"each exact", false, false}, {"quick, CPU", true, false}, {"quick, GPU", true, true}};

/// The first frame of a drag's quick variants: on the GPU it makes and uploads the frame's
/// terms (DynamicRelighting::movedLightFrame), once a drag.
void printFirst(const Samples& s, const Variant& v) {
    if (!v.quick || s.frame.empty()) return;
    std::printf("  its first frame: %.1f ms (upload %.1f ms)\n", s.frame.front(), s.upload.front());
}

void sunDrag(Session& session, FrameRenderer& frame, int frames, int upscale) {
    std::string sun;
    for (const LightControl& l : session.lights())
        if (l.emitter && radiosity::findField(*l.emitter, "direction")) sun = l.name;
    if (sun.empty()) throw std::runtime_error("the scene has no sun to drag");
    const Display& display = kDisplays[2];  // per-pixel
    for (const Variant& v : kDragVariants) {
        session.setQuickMoves(v.quick);
        frame.gpuLights = v.gpu;
        const Samples s = timeFrames(frame, display, frames, [&](int) {
            session.dragSun(sun, 1.0 * upscale, 0.5 * upscale);
        });
        printRow((std::string("sun drag, ") + v.name).c_str(), display, s);
        printFirst(s, v);
        if (session.exactPending()) printAtRest(session, frame, "drag");
    }
    frame.gpuLights = true;
}

/// A lamp (a point lamp `offset` metres above the floor, or a quad lamp on it) following the
/// pointer from pixel `at` along `step` in each of kDragVariants (Session::moveLightTo, the
/// pick through the lamp's own face), back and forth, one pass each, and the drag at rest.
struct LampDrag {
    Session& session;
    FrameRenderer& frame;
    int frames;
    std::array<double, 2> at, step;
    int misses = 0;
    bool forwards = true;

    void run(const std::string& what, const std::string& lamp, double offset) {
        const Display& display = kDisplays[2];  // per-pixel
        for (const Variant& v : kDragVariants) {
            session.setQuickMoves(v.quick);
            frame.gpuLights = v.gpu;
            const Samples s = timeFrames(frame, display, frames, [&](int i) {
                const double f = static_cast<double>(i + 1) / frames, t = forwards ? f : 1 - f;
                const Pick p = session.pick(at[0] + t * step[0], at[1] + t * step[1], lamp);
                if (p.hit)
                    session.moveLightTo(lamp, p, offset);
                else
                    ++misses;
            });
            printRow((what + ", " + v.name).c_str(), display, s);
            printFirst(s, v);
            if (session.exactPending()) printAtRest(session, frame, what.c_str());
            forwards = !forwards;
        }
        frame.gpuLights = true;
        session.setQuickMoves(false);
    }
};

/// A point lamp dragged over the floor and quad lamps inserted, in the per-pixel display
/// (issue 32 item 5's "lamp drag" and "lamp insertion"): the lamp is put 0.3 m above the
/// floor at pixel `at` and follows the pointer along `step` (the box's line, one pass),
/// each move first solved exactly, then with the window's quick frames
/// (Session::setQuickMoves; kDragVariants: the light per pixel on the CPU, then on the GPU)
/// and the drag at rest; then a virtual quad lamp inserted on the floor and taken out again,
/// min(frames, 8) times: the frame of each insertion; then the last one dragged as the point
/// lamp was (its GPU frames: four cube shadow maps).
void lampDragAndInsertion(Session& session, FrameRenderer& frame, int frames,
                          std::array<double, 2> at, std::array<double, 2> step) {
    const Display& display = kDisplays[2];  // per-pixel
    frame.framebuffer = display.framebuffer;
    frame.perPixel = display.perPixel;
    const std::string lamp = session.addPointLampAt(session.pick(at[0], at[1]), 0.3);
    frame.render();
    LampDrag drag{session, frame, frames, at, step};
    drag.run("point lamp drag", lamp, 0.3);
    session.removeLight(static_cast<int>(session.lights().size()) - 1);
    frame.render();
    const Pick floor = session.pick(at[0], at[1]);
    Samples s;
    for (int i = 0; i < std::min(frames, 8); ++i) {
        if (i > 0) {  // the last one taken out, not timed
            session.removeLight(static_cast<int>(session.lights().size()) - 1);
            frame.render();
        }
        s = concat(s, timeFrames(frame, display, 1, [&](int) { session.addLightAt(floor); }));
    }
    printRow("quad lamp insertion", display, s);
    if (session.exactPending()) printAtRest(session, frame, "insertion");
    // The last quad lamp inserted, dragged over the floor as the point lamp was
    // (Session::moveLightTo): each move inserted again, then the quick frames (its direct
    // light per pixel from one ray on the CPU; on the GPU from four cube shadow maps).
    drag.run("quad lamp drag", session.lights().back().name, 0);
    std::printf(
        "point lamp: 0.3 m over the floor, dragged %.0f px%s; quad lamp: on the floor at "
        "(%.1f, %.1f), inserted min(frames, 8) times (the last one taken out between, untimed), "
        "then dragged as the point lamp\n",
        std::hypot(step[0], step[1]), drag.misses ? " (some pointer positions missed)" : "", at[0],
        at[1]);
}

int run(const Args& a) {
    std::printf("command: ./build/bench/viewer_frames %s --scene %s --upscale %d --frames %d\n",
                a.data.c_str(), a.scene.c_str(), a.upscale, a.frames);
    const fs::path dir = fs::path(a.data) / a.scene;
    // The window before the preparation: without a display the bench fails at once.
    SceneFile sf = loadScene(dir);
    const int width = sf.camera.width * a.upscale, height = sf.camera.height * a.upscale;
    std::unique_ptr<GlWindow> window;
    std::unique_ptr<EglContext> egl;
    if (a.context == "egl")
        egl = std::make_unique<EglContext>(width, height);
    else
        window = std::make_unique<GlWindow>(width, height, "viewer_frames", false);
    std::printf("renderer: %s; %u hardware threads\n",
                (egl ? egl->renderer() : window->renderer()).c_str(),
                std::thread::hardware_concurrency());

    const TempDir tmp(fs::temp_directory_path() /
                      ("relight_viewer_frames_" + std::to_string(getpid())));
    if (a.upscale > 1) upscaleScene(sf, a.upscale, tmp.path);
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.pixelLight = true;  // the viewer's default display, per pixel, needs it
    const auto t0 = Clock::now();
    o.progress = [&](const std::string& m) {
        std::fprintf(stderr, "  [%6.1f s] %s\n", secondsSince(t0), m.c_str());
    };
    std::fprintf(stderr, "preparing %s at %dx%d\n", dir.c_str(), sf.camera.width, sf.camera.height);
    const std::unique_ptr<Relighting> r = prepareRelighting(std::move(sf), o);
    const PreparedImage& p = r->prepared;
    std::printf(
        "%s at %dx (photo %dx%d): preparation %.1f s (default options, epsilon %g); %d leaves, "
        "%d links, %zu leaf vertices\n",
        dir.c_str(), a.upscale, p.photo.width, p.photo.height, secondsSince(t0), o.epsilon,
        p.leaves, p.links, p.vertexCount());

    Session session(*r, EditFile{});
    GpuRatioDisplay gpu(session.prepared());
    FrameRenderer frame(session, gpu);
    {
        // As the viewer does when its window opens (viewer/main.cpp).
        const auto t1 = Clock::now();
        session.prepareMovedLightFrames();
        std::printf("the GPU frames of a moved sun or point lamp prepared: %.1f ms\n",
                    1e3 * secondsSince(t1));
    }
    std::printf(
        "%d frames per row; ms: median (90th percentile). update: Session::update or dragTo "
        "(the solver, on the CPU); upload: the values per vertex computed and sent to the GPU, "
        "with the virtual parts' overlay (its rays); draw: the photo area, glFinish included; "
        "fps = 1000 / median frame\n",
        a.frames);
    printHeader();
    if (a.scene != "room") {
        sunDrag(session, frame, a.frames, a.upscale);
        return 0;
    }
    lightSlider("light slider", session, frame, a.frames);

    // The box where the room's own virtual_box edit puts it: the pixel of its centre,
    // (1.25, 1.95, 0.15), in the camera at this resolution, which sees the floor behind it.
    const Camera& camera = r->scene.camera;
    double u = 0, v = 0, depth = 0;
    if (!camera.project({1.25, 1.95, 0.15}, u, v, depth))
        throw std::runtime_error("the box's place is behind the camera");
    const Pick floor = session.pick(u, v);
    if (!floor.hit || floor.normal.z < 0.9) throw std::runtime_error("no floor at the box's pixel");
    session.addBoxAt(floor);
    frame.render();
    lightSlider("light slider with a box", session, frame, a.frames);

    // The drag: grabbed where it was put, towards where virtual_box_moved puts the box (a
    // straight line over the floor, which the box stays on), 60 K pixels in all; forwards
    // in one display, back in the next, and so on, in one gesture.
    const Pick grab = session.pick(u, v);
    if (grab.object != 0) throw std::runtime_error("the box is not under its own pixel");
    double u1 = 0, v1 = 0;
    camera.project({0.7, 1.1, 0.0}, u1, v1, depth);
    const double length = 60.0 * a.upscale, towards = std::hypot(u1 - u, v1 - v);
    const double du = (u1 - u) / towards * length, dv = (v1 - v) / towards * length;
    const auto boxAt = [&] {
        const auto& m = session.objects().at(0).object.transform;
        return Vec3(m[0][3], m[1][3], m[2][3]);
    };
    const Vec3 start = boxAt();
    session.beginDrag(grab.object, grab);
    int misses = 0;
    Vec3 end = start;
    bool forwards = true;
    for (const Display& display : kDisplays) {
        const Samples s = timeFrames(frame, display, a.frames, [&](int i) {
            const double f = static_cast<double>(i + 1) / a.frames;
            const double t = forwards ? f : 1 - f;
            if (!session.dragTo(u + t * du, v + t * dv)) ++misses;
        });
        if (forwards) end = boxAt();
        printRow("box drag", display, s);
        forwards = !forwards;
    }
    // The same drag in the per-pixel display with the window's quick moves
    // (Session::setQuickMoves: DynamicRelighting::previewLastObject, the box's direct light
    // and shadows per pixel, the solver without it), then the pointer resting
    // (Session::settle: the box inserted where it is, render's image) and how far the last
    // quick frame was from it.
    session.setQuickMoves(true);
    const Samples quick = timeFrames(frame, kDisplays[2], a.frames, [&](int i) {
        const double f = static_cast<double>(i + 1) / a.frames;
        if (!session.dragTo(u + (forwards ? f : 1 - f) * du, v + (forwards ? f : 1 - f) * dv))
            ++misses;
    });
    printRow("box drag, quick", kDisplays[2], quick);
    if (session.exactPending()) printAtRest(session, frame, "drag");
    session.setQuickMoves(false);
    session.endDrag();
    const auto& m = session.objects().at(0).object.transform;  // the unit box scaled
    std::printf(
        "box: %.2f m on a side at pixel (%.1f, %.1f); with it %zu active links; dragged %.0f px "
        "from there towards (%.1f, %.1f): the box %.3f m over the floor and back%s\n",
        glm::length(Vec3(m[0][0], m[1][0], m[2][0])), u, v, session.links(), length, u1, v1,
        glm::length(end - start), misses ? " (some pointer positions missed its plane)" : "");
    lampDragAndInsertion(session, frame, a.frames, {u, v}, {du, dv});
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Args a;
    if (!parseArgs(argc, argv, a)) return 2;
    try {
        return run(a);
    } catch (const WindowError& e) {
        std::fprintf(stderr,
                     "viewer_frames: error: %s\n(run it as the top of bench/viewer_frames.cpp "
                     "says: under xvfb-run with LIBGL_ALWAYS_SOFTWARE=1)\n",
                     e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "viewer_frames: error: %s\n", e.what());
        return 1;
    }
}
