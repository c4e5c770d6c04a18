// relight-viewer <scene_dir> [--edit edit.json] [--screenshot out.png|exr] [options]
//
// Opens the relit photo in a window with a panel of the lights and virtual parts
// (viewer/app.h). With --screenshot it draws one frame (after --edit and the --do actions)
// at the photo's resolution, writes it like `relight render` does (linear values; PNG: sRGB
// transfer function, clipped to [0, 1], after --exposure stops) and exits.
// --do runs what a click would, in order, for scripts and tests:
//   light:U,V          a virtual light on the surface under photo pixel (U, V)
//   box:U,V            a box standing on the surface under (U, V)
//   drag:U0,V0:U1,V1   grabs the object under (U0, V0) and drags it to (U1, V1)
//   remove:U,V         takes out the removable real object under (U, V)
//   restore:NAME       brings back the real object NAME
//   lamp:U,V[:W,H]     a real lamp on the surface under (U, V), W x H metres (default: the
//                      size of the scene's lamps), its radiance estimated from the photo;
//                      --save-lamps adds the lamps placed to scene.json
// and what the panel's light controls do (radiosity/emitter.h: the same edit fields as a
// saved edit's, Session::editLight):
//   sun:NAME:AZ,EL     the sun NAME at azimuth AZ, elevation EL degrees (the sliders)
//   sundrag:NAME:U0,V0:U1,V1  the sun turned by a drag on the image (Session::dragSun)
//   rotate:NAME:X,Y,Z:DEG     the sky NAME turned by DEG degrees about the axis (X, Y, Z)
//   scale:NAME:S       the light NAME's strengths times S (a sky: every coefficient; a
//                      quad lamp: its intensity slider)
//   sh9:NAME:K:R,G,B   the sky NAME's coefficient K (0..8) set to (R, G, B)
//   point:U,V          a virtual point lamp above the surface under (U, V)
//   move:NAME:U,V      the point lamp or virtual quad lamp NAME moved onto the surface under
//                      (U, V) (a drag's end; Session::moveLightTo); movepoint: the same
// and the object panel's specular term (relight/dynamic/specular.h):
//   specular:NAME:R,G,B:S  the virtual object NAME's ks (R, G, B) and shininess S
//                      (ks 0,0,0: no term)
// With the window open (no --screenshot), the window runs them as it runs the panel's slow
// actions: one after another on its worker thread, drawing meanwhile; --window-screenshot
// waits for them, and the terminal prints how long each took; one that fails is a message
// in the panel, and the viewer's exit code is then 2 when the window closes.
// Errors (no display, no OpenGL 3.3, a scene or edit that does not load, a bad option, a
// screenshot that cannot be written) print one clear line and exit with 2 for bad input, 3
// for an output that cannot be written, 1 otherwise (relight/errors.h).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "radiosity/stopwatch.h"
#include "relight/cli/validators.h"
#include "relight/errors.h"
#include "relight/io/edit_file.h"
#include "relight/io/scene_file.h"
#include "relight/relighting.h"
#include "viewer/app.h"
#include "viewer/frame.h"
#include "viewer/gl_window.h"
#include "viewer/session.h"

using namespace relight;
using namespace relight::viewer;

namespace {

struct Args {
    std::string scene, edit, screenshot, saveEdit, framebuffer = "float", view = "relit";
    std::string display = "pixel";  // relight render's default display
    std::vector<std::string> actions;
    std::string windowShot;
    bool saveLamps = false;
    double exposure = 0, epsilon = RelightOptions{}.epsilon;
    double timeBudget = RelightOptions::kCommandTimeBudget;
    int spp = 16;
};

/// "U,V" -> pixel coordinates; throws std::invalid_argument naming the action.
void parsePoint(const std::string& text, const std::string& action, double& u, double& v) {
    std::istringstream in(text);
    char comma = 0;
    if (!(in >> u >> comma >> v) || comma != ',' || !in.eof())
        throw std::invalid_argument("--do " + action + ": \"" + text + "\" is not a pixel \"U,V\"");
}

/// "X,Y,Z" (`count` numbers, finite); throws std::invalid_argument naming the action.
std::vector<double> parseNumbers(const std::string& text, const std::string& action, size_t count) {
    std::istringstream in(text);
    std::vector<double> out;
    for (size_t k = 0; k < count; ++k) {
        double x = 0;
        char comma = ',';
        if ((k > 0 && (!(in >> comma) || comma != ',')) || !(in >> x) || !std::isfinite(x)) break;
        out.push_back(x);
    }
    if (out.size() == count) in >> std::ws;
    if (out.size() != count || !in.eof())
        throw std::invalid_argument("--do " + action + ": \"" + text + "\" is not " +
                                    std::to_string(count) + " numbers separated by commas");
    return out;
}

/// One --do action, parsed before the preparation so that a typo fails at once.
struct Action {
    std::string text;  ///< as given, for messages
    enum class Kind {
        light,
        box,
        drag,
        remove,
        restore,
        lamp,
        sun,
        sundrag,
        rotate,
        scale,
        sh9,
        point,
        specular,
        movepoint
    } kind = Kind::light;
    double u = 0, v = 0, u1 = 0, v1 = 0;  ///< pixel; drag: from (u, v) to (u1, v1)
    double width = 0, height = 0;         ///< lamp: its size in metres (0: the default)
    std::string name;                     ///< restore: the object; a light's name
    std::vector<double> numbers;          ///< sun: AZ, EL; rotate: X, Y, Z, DEG; ...
};

/// "NAME:REST" of a light action; throws naming the action when there is no name.
std::string splitName(const std::string& rest, const std::string& text, std::string& tail) {
    const auto sep = rest.find(':');
    if (sep == std::string::npos || sep == 0)
        throw std::invalid_argument("--do " + text + ": expected a light's name and values");
    tail = rest.substr(sep + 1);
    return rest.substr(0, sep);
}

/// The light controls' actions (sun, sundrag, rotate, scale, sh9, point, movepoint).
bool parseLightAction(Action& a, const std::string& kind, const std::string& rest) {
    const std::string& text = a.text;
    std::string tail;
    if (kind == "point") {
        a.kind = Action::Kind::point;
        parsePoint(rest, text, a.u, a.v);
    } else if (kind == "sun" || kind == "scale") {
        a.kind = kind == "sun" ? Action::Kind::sun : Action::Kind::scale;
        a.name = splitName(rest, text, tail);
        a.numbers = parseNumbers(tail, text, kind == "sun" ? 2 : 1);
        if (kind == "scale" && a.numbers[0] < 0)
            throw std::invalid_argument("--do " + text + ": a scale must not be negative");
    } else if (kind == "move" || kind == "movepoint") {
        a.kind = Action::Kind::movepoint;
        a.name = splitName(rest, text, tail);
        parsePoint(tail, text, a.u, a.v);
    } else if (kind == "sundrag") {
        a.kind = Action::Kind::sundrag;
        a.name = splitName(rest, text, tail);
        const auto sep = tail.find(':');
        if (sep == std::string::npos)
            throw std::invalid_argument("--do " + text + ": expected sundrag:NAME:U0,V0:U1,V1");
        parsePoint(tail.substr(0, sep), text, a.u, a.v);
        parsePoint(tail.substr(sep + 1), text, a.u1, a.v1);
    } else if (kind == "specular") {
        a.kind = Action::Kind::specular;
        a.name = splitName(rest, text, tail);
        const auto sep = tail.find(':');
        if (sep == std::string::npos)
            throw std::invalid_argument("--do " + text + ": expected specular:NAME:R,G,B:S");
        a.numbers = parseNumbers(tail.substr(0, sep), text, 3);
        a.numbers.push_back(parseNumbers(tail.substr(sep + 1), text, 1)[0]);
        if (a.numbers[0] < 0 || a.numbers[1] < 0 || a.numbers[2] < 0)
            throw std::invalid_argument("--do " + text + ": ks must be >= 0");
        if (!(a.numbers[3] > 0))
            throw std::invalid_argument("--do " + text + ": the shininess must be > 0");
    } else if (kind == "rotate" || kind == "sh9") {
        a.kind = kind == "rotate" ? Action::Kind::rotate : Action::Kind::sh9;
        a.name = splitName(rest, text, tail);
        const auto sep = tail.find(':');
        if (sep == std::string::npos)
            throw std::invalid_argument(
                "--do " + text + ": expected " +
                (kind == "rotate" ? "rotate:NAME:X,Y,Z:DEG" : "sh9:NAME:K:R,G,B"));
        const auto first = parseNumbers(tail.substr(0, sep), text, kind == "rotate" ? 3 : 1);
        const auto second = parseNumbers(tail.substr(sep + 1), text, kind == "rotate" ? 1 : 3);
        a.numbers = first;
        a.numbers.insert(a.numbers.end(), second.begin(), second.end());
        if (kind == "sh9" && !(a.numbers[0] >= 0 && a.numbers[0] < radiosity::kSh9Count &&
                               a.numbers[0] == std::floor(a.numbers[0])))
            throw std::invalid_argument("--do " + text + ": K must be 0 to 8");
    } else {
        return false;
    }
    return true;
}

Action parseAction(const std::string& text) {
    Action a;
    a.text = text;
    const auto colon = text.find(':');
    const std::string kind = text.substr(0, colon);
    const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
    if (parseLightAction(a, kind, rest)) return a;
    if (kind == "light" || kind == "box" || kind == "remove") {
        a.kind = kind == "light" ? Action::Kind::light
                 : kind == "box" ? Action::Kind::box
                                 : Action::Kind::remove;
        parsePoint(rest, text, a.u, a.v);
    } else if (kind == "lamp") {
        a.kind = Action::Kind::lamp;
        const auto sep = rest.find(':');
        parsePoint(rest.substr(0, sep), text, a.u, a.v);
        if (sep != std::string::npos) {
            parsePoint(rest.substr(sep + 1), text, a.width, a.height);
            if (!(a.width > 0 && a.height > 0 && std::isfinite(a.width) && std::isfinite(a.height)))
                throw std::invalid_argument("--do " + text + ": the size must be positive");
        }
    } else if (kind == "restore" && !rest.empty()) {
        a.kind = Action::Kind::restore;
        a.name = rest;
    } else if (kind == "drag") {
        a.kind = Action::Kind::drag;
        const auto sep = rest.find(':');
        if (sep == std::string::npos)
            throw std::invalid_argument("--do " + text + ": expected drag:U0,V0:U1,V1");
        parsePoint(rest.substr(0, sep), text, a.u, a.v);
        parsePoint(rest.substr(sep + 1), text, a.u1, a.v1);
    } else {
        throw std::invalid_argument("--do " + text +
                                    ": unknown action (light:U,V, box:U,V, drag:U0,V0:U1,V1, "
                                    "remove:U,V, restore:NAME, lamp:U,V[:W,H], sun:NAME:AZ,EL, "
                                    "sundrag:NAME:U0,V0:U1,V1, rotate:NAME:X,Y,Z:DEG, "
                                    "scale:NAME:S, sh9:NAME:K:R,G,B, point:U,V, "
                                    "move:NAME:U,V, specular:NAME:R,G,B:S)");
    }
    return a;
}

/// The light controls' actions; false for the others.
bool runLightAction(Session& s, const Action& a) {
    radiosity::EmitterEdit e;
    switch (a.kind) {
        case Action::Kind::sun:
            e.direction = Session::sunDirection(a.numbers[0], a.numbers[1]);
            break;
        case Action::Kind::sundrag:
            try {
                // With quick moves (the per-pixel displays, Session::setQuickMoves), the
                // pointer's path in steps of about a pixel, as a mouse reports it, each a
                // quick frame; else one turn, solved once.
                const int steps =
                    s.quickMoves()
                        ? std::max(1, static_cast<int>(std::hypot(a.u1 - a.u, a.v1 - a.v)))
                        : 1;
                for (int k = 0; k < steps; ++k)
                    s.dragSun(a.name, (a.u1 - a.u) / steps, (a.v1 - a.v) / steps);
            } catch (const std::invalid_argument& ex) {
                throw InputError("--do " + a.text + ": " + ex.what());
            }
            return true;
        case Action::Kind::rotate:
            e.rotate = radiosity::EmitterEdit::Rotation{
                Vec3(a.numbers[0], a.numbers[1], a.numbers[2]), a.numbers[3]};
            break;
        case Action::Kind::scale:
            // A quad lamp: what its intensity slider does (a sun, lamp or sky: an edit field).
            for (LightControl& l : s.lights())
                if (l.name == a.name && !l.emitter) {
                    l.intensity *= a.numbers[0];
                    s.update();
                    return true;
                }
            e.scale = a.numbers[0];
            break;
        case Action::Kind::sh9: {
            const radiosity::Emitter* em = s.emitter(a.name);
            if (!em || em->components() != radiosity::kSh9Count)
                throw InputError("--do " + a.text + ": no sky \"" + a.name + "\"");
            radiosity::Sh9Rgb L;
            const std::vector<Rgb> now = em->strengths();
            std::copy(now.begin(), now.end(), L.c.begin());
            L.c[static_cast<size_t>(a.numbers[0])] = Rgb{a.numbers[1], a.numbers[2], a.numbers[3]};
            e.sh9 = L;
            break;
        }
        case Action::Kind::point: {
            const Pick p = s.pick(a.u, a.v);
            if (!p.hit)
                throw std::invalid_argument("--do " + a.text + ": no surface at that pixel");
            s.addPointLampAt(p);
            return true;
        }
        case Action::Kind::movepoint:
            try {
                s.moveLightTo(a.name, s.pick(a.u, a.v, a.name));
            } catch (const std::invalid_argument& ex) {
                throw InputError("--do " + a.text + ": " + ex.what());
            }
            return true;
        case Action::Kind::specular: {
            const auto& objects = s.objects();
            const auto it = std::find_if(objects.begin(), objects.end(),
                                         [&](const auto& o) { return o.object.name == a.name; });
            if (it == objects.end())
                throw InputError("--do " + a.text + ": no virtual object \"" + a.name + "\"");
            const Rgb ks{a.numbers[0], a.numbers[1], a.numbers[2]};
            s.setSpecular(static_cast<int>(it - objects.begin()),
                          ks.maxComponent() > 0
                              ? std::optional<Specular>(Specular{ks, a.numbers[3]})
                              : std::nullopt);
            return true;
        }
        default:
            return false;
    }
    try {
        s.editLight(a.name, e);
    } catch (const std::invalid_argument& ex) {
        // Bad input (exit code 2): a light the scene lacks, a field its type lacks.
        throw InputError("--do " + a.text + ": " + ex.what());
    }
    return true;
}

/// Does what the click (or the drag) would do in the window.
void runAction(Session& s, const Action& a) {
    if (runLightAction(s, a)) return;
    if (a.kind == Action::Kind::restore) {
        if (std::find(s.removedObjects().begin(), s.removedObjects().end(), a.name) ==
            s.removedObjects().end())
            throw InputError("--do " + a.text + ": \"" + a.name + "\" is not taken out");
        s.restoreRealObject(a.name);
        return;
    }
    const Pick p = s.pick(a.u, a.v);
    if (a.kind == Action::Kind::remove) {
        if (p.realObject.empty())
            throw InputError("--do " + a.text + ": no removable real object at that pixel");
        s.removeRealObject(p.realObject);
        return;
    }
    if (a.kind != Action::Kind::drag) {
        if (!p.hit) throw std::invalid_argument("--do " + a.text + ": no surface at that pixel");
        if (a.kind == Action::Kind::lamp)
            s.placeLampAt(p, a.width, a.height);
        else if (a.kind == Action::Kind::light)
            s.addLightAt(p);
        else
            s.addBoxAt(p);
        return;
    }
    if (p.object < 0)
        throw std::invalid_argument("--do " + a.text + ": no virtual object at the first pixel");
    s.beginDrag(p.object, p);
    // The pointer's path in steps of about a pixel, as a mouse would report it.
    const int steps = std::max(1, static_cast<int>(std::hypot(a.u1 - a.u, a.v1 - a.v)));
    for (int k = 1; k <= steps; ++k) {
        const double f = static_cast<double>(k) / steps;
        s.dragTo(a.u + f * (a.u1 - a.u), a.v + f * (a.v1 - a.v));
    }
    s.endDrag();
}

int run(const Args& a) {
    // Everything that can fail fast does, before the preparation: the scene, the edit, the
    // display and the OpenGL context.
    const auto start = radiosity::Clock::now();  // the preparation's budget counts from here
    SceneFile sf = loadScene(a.scene);
    EditFile edit;
    if (!a.edit.empty()) {
        edit = loadEdit(a.edit, sf);
    }
    for (const std::string& w : edit.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::vector<Action> actions;
    for (const std::string& text : a.actions) {
        // A --do that does not parse is bad input (exit code 2), as a bad option is.
        try {
            actions.push_back(parseAction(text));
        } catch (const std::invalid_argument& e) {
            throw InputError(e.what());
        }
    }
    const ViewKind view = parseView(a.view);
    if (a.framebuffer != "float" && a.framebuffer != "multipass")
        throw std::invalid_argument("--framebuffer must be float or multipass");
    const bool interactive = a.screenshot.empty();
    const int pw = sf.camera.width, ph = sf.camera.height;
    // The photo at up to 3x, within 1600 x 1000 with the panel beside it.
    const double zoom = std::max(1.0, std::min({3.0, 1240.0 / pw, 1000.0 / ph}));
    GlWindow window(static_cast<int>(pw * zoom) + 360, static_cast<int>(ph * zoom),
                    "relight-viewer " + a.scene, interactive);
    std::fprintf(stderr, "relight-viewer: %s\n", window.renderer().c_str());

    RelightOptions o;
    o.budgetStart = start;
    o.epsilon = a.epsilon;
    o.timeBudget = a.timeBudget;
    o.spp = a.spp;
    const DisplayMode mode = parseDisplayMode(a.display);
    o.pixelLight = drawsPerPixel(mode);
    o.progress = [](const std::string& m) { std::fprintf(stderr, "  %s\n", m.c_str()); };
    std::fprintf(stderr, "relight-viewer: preparing %s\n", a.scene.c_str());
    // Its polygons go to the solver, not copied: prepared->scene is the scene from here on.
    const std::unique_ptr<Relighting> prepared = prepareRelighting(std::move(sf), o);
    Session session(*prepared, edit);
    for (const std::string& w :
         virtualLightReachWarnings(edit, prepared->solver->scene(), prepared->solver->visibility(),
                                   static_cast<size_t>(session.realLights())))
        std::fprintf(stderr, "warning: %s\n", w.c_str());
    // A sun or lamp moved shows quick frames in the per-pixel displays, as the window's.
    session.setQuickMoves(drawsPerPixel(mode));
    // In the window, the actions run as the panel's slow ones do: on its worker thread, one
    // after another, the window drawing meanwhile (viewer/app.h); a failed one is a message, and
    // the exit code 2 once the window closes.
    AppOptions ao;
    for (const Action& act : actions) {
        if (interactive)
            ao.actions.push_back({"--do " + act.text, [act](Session& s) { runAction(s, act); }});
        else
            runAction(session, act);
    }
    // The image as `relight render` draws the edit, not a slider's quick one.
    if (!interactive && session.exactPending()) {
        std::printf("the quick image made exact (Session::settle)\n");
        session.settle();
    }
    GpuRatioDisplay display(session.prepared());
    FrameRenderer frame(session, display);
    frame.view = view;
    frame.framebuffer = a.framebuffer == "float" ? Framebuffer::float32 : Framebuffer::multipass8;
    frame.exposure = a.exposure;
    frame.perPixel = drawsPerPixel(mode);
    if (frame.perPixel) frame.perPixelMode = mode;
    // The first frame, refused when not finite before it is shown or anything is written
    // (the session refuses a radiance that overflows; a finite one may overflow the floats).
    const FrameStats s = frame.render();
    const Image img = frame.read();
    requireFiniteImage(img, prepared->scene, edit,
                       editRadiance(prepared->scene, edit, prepared->prepared.photoRadiance),
                       view == ViewKind::relit ? "the relit image"
                                               : std::string("the ") + viewName(view) + " view");
    if (!a.saveEdit.empty() && !interactive) {
        session.save(a.saveEdit);
        std::printf("wrote %s\n", a.saveEdit.c_str());
    }
    if (a.saveLamps && !interactive && !session.placedLamps().empty()) {
        const size_t n = session.placedLamps().size();
        session.saveLamps(a.scene);
        std::printf("added %zu lamp%s to %s/scene.json\n", n, n == 1 ? "" : "s", a.scene.c_str());
    }
    if (!interactive) {
        writeImage(a.screenshot, img);  // exposure already applied by the display
        std::printf("wrote %s (%dx%d, %s framebuffer, %d pass%s, draw %.1f ms)\n",
                    a.screenshot.c_str(), img.width, img.height, a.framebuffer.c_str(), s.passes,
                    s.passes == 1 ? "" : "es", 1e3 * s.draw);
        return 0;
    }
    if (!a.saveEdit.empty()) ao.saveFile = a.saveEdit;
    ao.windowShot = a.windowShot;
    if (frame.perPixel && frame.gpuLights && frame.perPixelMode == DisplayMode::pixel) {
        const auto t0 = radiosity::Clock::now();
        if (session.prepareMovedLightFrames())
            std::printf(
                "the GPU frames of a sun or point lamp being moved: the photo's pooled "
                "reflectance made (%.0f ms)\n",
                1e3 * radiosity::secondsSince(t0));
    }
    return runApp(window, session, frame, ao);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"relight-viewer: relight a photographed room by hand (Loscos et al. 2000)"};
    Args a;
    app.add_option("scene_dir", a.scene, "scene folder holding scene.json")->required();
    app.add_option("--edit", a.edit, "relight-edit/1 JSON file to start from");
    app.add_option("--screenshot", a.screenshot,
                   "draw one frame, write it (.png sRGB 8-bit, .exr linear) and exit");
    app.add_option("--window-screenshot", a.windowShot,
                   "open the window, write all of it (panel included) after a few frames, exit");
    app.add_option("--exposure", a.exposure, "exposure in stops")
        ->check(cli::finiteNumber(cli::Sign::kAny));
    app.add_option("--framebuffer", a.framebuffer,
                   "float (one pass) or multipass (8-bit, the paper's §5.3 passes)");
    app.add_option("--view", a.view, "relit, mesh, B, D, T_orig, T_final, reflectance or frontier");
    app.add_option("--display", a.display,
                   "the relit view: pixel (the default, as relight render's: the direct light "
                   "per pixel, Loscos et al. 1999, drawn on the CPU; prepares the per-pixel "
                   "light), ratio-map (000 Eq. 3: the direct light alone) and wen (the sky "
                   "unoccluded, Wen et al. 2003), drawn on the CPU as relight render draws "
                   "them, or ratio (Loscos et al. 2000 vertex ratios, on the GPU)")
        ->capture_default_str()
        ->check(CLI::IsMember({"ratio", "pixel", "ratio-map", "wen"}));
    app.add_option("--do", a.actions,
                   "light:U,V | box:U,V | drag:U0,V0:U1,V1 | remove:U,V | restore:NAME | "
                   "lamp:U,V[:W,H] | specular:NAME:R,G,B:S (in order)");
    app.add_flag("--save-lamps", a.saveLamps,
                 "with --screenshot: add the real lamps placed (--do lamp:...) to scene.json");
    app.add_option("--save-edit", a.saveEdit,
                   "with --screenshot: write the session's edit here; else the panel's default");
    app.add_option("--epsilon", a.epsilon, "BF refinement threshold")
        ->capture_default_str()
        ->check(cli::finiteNumber(cli::Sign::kPositive));
    app.add_option("--spp", a.spp, "camera samples per pixel")->check(CLI::Range(1, 1024));
    // As relight's: a phase past its share takes a coarser fallback it announces on stderr.
    app.add_option("--time-budget", a.timeBudget,
                   "seconds the preparation may take from the start, split over its phases "
                   "as relight render's --time-budget (0: no limit)")
        ->capture_default_str()
        ->check(cli::finiteNumber(cli::Sign::kNonNegative));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help as CLI11 prints it; a bad option is bad input: one line, exit code 2 (as
        // `relight`), not CLI11's own codes.
        if (e.get_exit_code() == 0) return app.exit(e);
        std::fprintf(stderr, "relight-viewer: error: %s; see relight-viewer --help\n", e.what());
        return 2;
    }
    try {
        return run(a);
    } catch (const std::exception& e) {  // a WindowError too: exit code 1
        std::fprintf(stderr, "relight-viewer: error: %s\n", e.what());
        return exitCode(e);
    }
}
