#include "viewer/app.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <exception>
#include <filesystem>
#include <functional>
#include <optional>
#include <utility>

#include "viewer/background_work.h"
#include "viewer/mouse_tools.h"

namespace relight::viewer {

namespace {

constexpr float kPanelWidth = 360.0f;  ///< window pixels

PhotoRect photoRect(int winW, int winH, int photoW, int photoH) {
    const double areaW = std::max(1.0, winW - static_cast<double>(kPanelWidth));
    const double s = std::min(areaW / photoW, static_cast<double>(winH) / photoH);
    PhotoRect r;
    r.w = photoW * s;
    r.h = photoH * s;
    r.x = 0.5 * (areaW - r.w);
    r.y = 0.5 * (winH - r.h);
    return r;
}

class App {
  public:
    App(GlWindow& window, Session& session, FrameRenderer& frame, const AppOptions& o)
        : window_(window),
          session_(session),
          frame_(frame),
          windowShot_(o.windowShot),
          script_(o.actions.begin(), o.actions.end()),
          tools_(session, ToolHost{[this](const char* what, const std::function<void()>& f) {
                                       return act(what, f);
                                   },
                                   [this](std::string what, std::function<void()> work) {
                                       inBackground(std::move(what), std::move(work));
                                   },
                                   [this] { return work_.busy(); }}) {
        std::snprintf(savePath_, sizeof savePath_, "%s", o.saveFile.c_str());
    }

    /// Returns the exit code: 2 when a scripted action (AppOptions::actions) failed.
    int run();

  private:
    void panel();
    void beginPanel();  ///< the panel's window, right of the photo, the window's height
    /// The overlay's window, over the photo's top left corner; it takes no input.
    void beginOverlay(const PhotoRect& r);
    void lightsPanel();
    /// A light's control edited this frame (`edited`) or let go (`letGo`).
    void lightChange(bool edited, bool letGo);
    void emitterControls(LightControl& l);
    void skyControls(const LightControl& l, const radiosity::EmitterField& sh9);
    void objectsPanel();
    void specularControls(int i);  ///< object i's specular term (its ks, shininess)
    void displayPanel();
    void lampsPanel();
    void drawLamps(const PhotoRect& r);
    void statsOverlay(const PhotoRect& r);
    /// The pointer from GLFW, to the tools (viewer/mouse_tools.h).
    void mouse(const PhotoRect& r);
    /// One frame's input: the end of the work in the background, the next scripted action,
    /// then the panel and the mouse, or busyPanel() while work runs.
    void interact(const PhotoRect& r);
    /// Whether f ran without throwing.
    bool act(const char* what, const std::function<void()>& f);
    /// Runs `work` on the worker thread (BackgroundWork) and returns at once; the next
    /// frames show the last image and busyPanel() until it ends. `work` must capture what
    /// it uses by value: the caller's frame is gone when it runs.
    void inBackground(std::string what, std::function<void()> work);
    /// Records a slow action of the panel (one that solves, gathers or inserts the parts
    /// again), which interact() starts with inBackground() once panel() has returned: the panel
    /// reads the session until its end, so the work may not begin while it is drawn. `work`
    /// captures by value what it needs (the slider's new value, a name, an index), never
    /// ImGui's state. One a frame: a click edits one control.
    void later(const char* what, std::function<void()> work);
    /// The panel and overlay while work runs: what is being done, for how long, and what
    /// the image shows meanwhile. Reads nothing of the session.
    void busyPanel(const PhotoRect& r);

    GlWindow& window_;
    Session& session_;
    FrameRenderer& frame_;
    char savePath_[1024] = {};
    std::string status_;
    FrameStats stats_;
    double frameSeconds_ = 0, lastUpdate_ = 0;
    double lastChange_ = 0;  ///< glfwGetTime() when the image last changed
    /// How long a slider rests before its quick image is made exact (Session::settle):
    /// longer than between two mouse reports while it moves, short enough not to be waited for.
    static constexpr double kSettleSeconds = 0.25;
    std::string windowShot_;
    float sliders_[2] = {0, 0};  ///< the sun's azimuth and elevation while a slider is held
    float skyTurn_ = 15.0f;      ///< degrees the sky's "turn about z" button turns it
    BackgroundWork work_;
    /// A slow action of the panel, started after it is drawn (later()).
    struct Deferred {
        std::string what;
        std::function<void()> work;
    };
    std::optional<Deferred> deferred_;
    std::deque<ScriptedAction> script_;  ///< AppOptions::actions not yet started
    bool scriptRunning_ = false;         ///< the work in the background is a scripted action
    /// A scripted action failed: bad input on the command line (--do), exit code 2 as
    /// without the window, once the window closes.
    bool scriptFailed_ = false;
    std::string busyFrom_;    ///< what the image showed when the work began
    int busyFrames_ = 0;      ///< frames drawn while the work ran
    double busyLongest_ = 0;  ///< the longest of them (seconds)
    MouseTools tools_;        ///< the mouse on the photo: the panel's tool and its drags
};

/// The window's back buffer (sRGB-encoded bytes) as a linear image, rows from the top.
Image readWindow(int w, int h) {
    std::vector<unsigned char> bytes(static_cast<size_t>(w) * h * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c)
                img.at(x, h - 1 - y)[c] = static_cast<float>(
                    srgbDecode(bytes[(static_cast<size_t>(y) * w + x) * 4 + c] / 255.0));
    return img;
}

bool App::act(const char* what, const std::function<void()>& f) {
    // A failed action (a degenerate pick, a file that cannot be written) is a message in the
    // panel, never the end of the session.
    try {
        f();
        return true;
    } catch (const std::exception& e) {
        status_ = std::string(what) + " failed: " + e.what();
        std::fprintf(stderr, "relight-viewer: %s\n", status_.c_str());
        return false;
    }
}

void App::beginPanel() {
    int winW = 0, winH = 0;
    glfwGetWindowSize(window_.handle(), &winW, &winH);
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(winW) - kPanelWidth, 0));
    ImGui::SetNextWindowSize(ImVec2(kPanelWidth, static_cast<float>(winH)));
    ImGui::Begin("relight", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
}

void App::beginOverlay(const PhotoRect& r) {
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(r.x) + 8, static_cast<float>(r.y) + 8));
    ImGui::SetNextWindowBgAlpha(0.55f);
    ImGui::Begin("stats", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoInputs | ImGuiWindowFlags_NoSavedSettings);
}

void App::inBackground(std::string what, std::function<void()> work) {
    busyFrom_ = session_.exactPending() ? session_.stage() : "exact";
    busyFrames_ = 0;
    busyLongest_ = 0;
    // The per-pixel display's image of the result is made there too: made by the frame after
    // (FrameRenderer::render), its shadow rays would hold that frame instead. The display's
    // settings, read here, cannot change while the work runs (no panel).
    const bool perPixel = frame_.view == ViewKind::relit && frame_.perPixel;
    const DisplayMode mode = frame_.perPixelMode;
    work_.start(std::move(what), [this, work = std::move(work), perPixel, mode] {
        work();
        if (perPixel) frame_.prepareImage(mode);
    });
}

void App::later(const char* what, std::function<void()> work) {
    deferred_ = Deferred{what, std::move(work)};
}

void App::lightChange(bool edited, bool letGo) {
    if (!edited && !letGo) return;
    // The quick image at once, each frame a slider moves (Session::updateQuickly: the
    // superposition, or the quick path with virtual objects, exact when the slider rests).
    // A change that inserts the parts again (a virtual lamp's strength; a real lamp's with a
    // virtual lamp in) waits until the control is let go, then runs in the background: started
    // while the slider is held, the busy panel would take the slider from under the hand.
    bool quick = true;
    act("light change", [&] { quick = session_.updateQuickly(); });
    if (!quick && letGo) later("light change", [this] { session_.update(); });
}

void App::busyPanel(const PhotoRect& r) {
    // Drawn instead of the panel while the work runs: no control, so nothing of the session
    // is read or changed while the worker holds it.
    beginPanel();
    ImGui::TextWrapped("Catching up in the background: %s (%.1f s).", work_.what().c_str(),
                       work_.seconds());
    ImGui::TextWrapped(
        "The window stays live; the controls wait until the exact image is ready, which is "
        "what `relight render` draws of the edit.");
    ImGui::End();
    beginOverlay(r);
    ImGui::Text("frame %.1f ms (%.0f fps)", 1e3 * frameSeconds_,
                static_cast<double>(ImGui::GetIO().Framerate));
    ImGui::TextWrapped("shown meanwhile: the last image (%s)", busyFrom_.c_str());
    ImGui::Text("being made: the exact image, %.1f s", work_.seconds());
    ImGui::End();
}

void App::lightsPanel() {
    if (!ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) return;
    auto& lights = session_.lights();
    int remove = -1;
    for (size_t i = 0; i < lights.size(); ++i) {
        LightControl& l = lights[i];
        // A sun, point lamp or sky: one entry for all its components.
        if (l.emitter && l.component != 0) continue;
        ImGui::PushID(static_cast<int>(i));
        const std::string label = l.name +
                                  (l.emitter ? std::string(" (") + l.emitter->type() + ")" : "") +
                                  (l.isVirtual ? " (virtual)" : "");
        const bool toggled = ImGui::Checkbox(label.c_str(), &l.on);
        bool changed = toggled, letGo = toggled;
        if (l.isVirtual) {
            ImGui::SameLine();
            if (ImGui::SmallButton("remove")) remove = static_cast<int>(i);
        }
        // A virtual quad lamp is dragged over the surfaces (Session::moveLightTo).
        if (l.isVirtual && !l.emitter &&
            ImGui::RadioButton("move it: drag on a surface",
                               tools_.tool == Tool::movePoint && tools_.point == l.name)) {
            tools_.tool = Tool::movePoint;
            tools_.point = l.name;
        }
        if (l.emitter) {
            for (LightControl& o : lights)  // its components follow its switch
                if (o.emitter == l.emitter) o.on = l.on;
            lightChange(changed, letGo);
            emitterControls(l);
            ImGui::PopID();
            continue;
        }
        float c[3] = {static_cast<float>(l.colour.r), static_cast<float>(l.colour.g),
                      static_cast<float>(l.colour.b)};
        if (ImGui::ColorEdit3("colour", c, ImGuiColorEditFlags_Float)) {
            l.colour = Rgb{c[0], c[1], c[2]};
            changed = true;
        }
        letGo = letGo || ImGui::IsItemDeactivatedAfterEdit();
        float intensity = static_cast<float>(l.intensity);
        if (ImGui::SliderFloat("intensity", &intensity, 0.0f, 60.0f, "%.2f",
                               ImGuiSliderFlags_Logarithmic)) {
            l.intensity = std::max(0.0f, intensity);
            changed = true;
        }
        letGo = letGo || ImGui::IsItemDeactivatedAfterEdit();
        lightChange(changed, letGo);
        ImGui::PopID();
    }
    if (remove >= 0) later("removing the light", [this, remove] { session_.removeLight(remove); });
}

/// The controls of a sun, point lamp or sky, from the fields it has (radiosity::Emitter::
/// fields): a direction (az/el sliders, the sun tool), a position (the move tool), sh9 (the
/// sky's), its strength. Each change is the edit field `relight render` reads
/// (Session::editLight), applied when the control is let go, in the background (a sun or
/// lamp moved is solved again as a virtual light, seconds on a large scene).
void App::emitterControls(LightControl& l) {
    const std::string name = l.name;
    if (const auto d = radiosity::findField(*l.emitter, "direction")) {
        double az = 0, el = 0;
        Session::sunAngles(Vec3(d->values[0], d->values[1], d->values[2]), az, el);
        if (!ImGui::IsAnyItemActive()) {
            sliders_[0] = static_cast<float>(az);
            sliders_[1] = static_cast<float>(el);
        }
        // In the per-pixel displays the sun follows the slider (quick frames,
        // Session::setQuickMoves); in the ratio display it turns when the slider is let go.
        const bool follow = session_.quickMoves();
        bool turn = ImGui::SliderFloat("azimuth", &sliders_[0], -180.0f, 180.0f, "%.1f deg");
        bool release = ImGui::IsItemDeactivatedAfterEdit();
        turn = ImGui::SliderFloat("elevation", &sliders_[1], -10.0f, 90.0f, "%.1f deg") || turn;
        release = release || ImGui::IsItemDeactivatedAfterEdit();
        radiosity::EmitterEdit e;
        e.direction = Session::sunDirection(sliders_[0], sliders_[1]);
        // Followed: each move a quick frame (DynamicRelighting::previewEmitter), at once.
        if (release)
            later("turning the sun", [this, name, e] { session_.editLight(name, e); });
        else if (follow && turn)
            act("turning the sun", [&] { session_.editLight(name, e); });
        if (ImGui::RadioButton("turn it by dragging on the image",
                               tools_.tool == Tool::sun && tools_.sun == name)) {
            tools_.tool = Tool::sun;
            tools_.sun = name;
        }
    }
    if (radiosity::findField(*l.emitter, "position") &&
        ImGui::RadioButton("move it: click a surface",
                           tools_.tool == Tool::movePoint && tools_.point == name)) {
        tools_.tool = Tool::movePoint;
        tools_.point = name;
    }
    if (const auto sh9 = radiosity::findField(*l.emitter, "sh9")) skyControls(l, *sh9);
    if (const auto s = radiosity::findField(*l.emitter, l.emitter->strengthKey());
        s && s->values.size() == 3) {
        float c[3] = {static_cast<float>(s->values[0]), static_cast<float>(s->values[1]),
                      static_cast<float>(s->values[2])};
        ImGui::DragFloat3(l.emitter->strengthKey(), c, 0.01f, 0.0f, 1e6f, "%.3f");
        if (ImGui::IsItemDeactivatedAfterEdit()) {
            radiosity::EmitterEdit e;
            e.strength = Rgb{std::max(0.0f, c[0]), std::max(0.0f, c[1]), std::max(0.0f, c[2])};
            later("light change", [this, name, e] { session_.editLight(name, e); });
        }
    }
}

/// A sky: turned about the vertical, scaled, and set coefficient by coefficient (the
/// format's basis, docs/scene-format.md).
void App::skyControls(const LightControl& l, const radiosity::EmitterField& sh9) {
    const std::string name = l.name;
    ImGui::DragFloat("turn (deg)", &skyTurn_, 1.0f, -180.0f, 180.0f, "%.0f");
    ImGui::SameLine();
    if (ImGui::SmallButton("turn about z")) {
        radiosity::EmitterEdit e;
        e.rotate = radiosity::EmitterEdit::Rotation{Vec3(0, 0, 1), skyTurn_};
        later("turning the sky", [this, name, e] { session_.editLight(name, e); });
    }
    for (const double k : {0.8, 1.25}) {
        char label[32];
        std::snprintf(label, sizeof label, "scale x%.2f", k);
        if (ImGui::SmallButton(label)) {
            radiosity::EmitterEdit e;
            e.scale = k;
            later("scaling the sky", [this, name, e] { session_.editLight(name, e); });
        }
        ImGui::SameLine();
    }
    ImGui::NewLine();
    if (!ImGui::TreeNode("coefficients L00 ... L22")) return;
    for (size_t k = 0; 3 * k + 2 < sh9.values.size(); ++k) {
        float c[3] = {static_cast<float>(sh9.values[3 * k]),
                      static_cast<float>(sh9.values[3 * k + 1]),
                      static_cast<float>(sh9.values[3 * k + 2])};
        ImGui::PushID(static_cast<int>(k));
        ImGui::DragFloat3("", c, 0.005f, -1e3f, 1e3f, "%.3f");
        if (ImGui::IsItemDeactivatedAfterEdit()) {
            radiosity::EmitterEdit e;
            radiosity::Sh9Rgb L;
            for (size_t j = 0; j < L.c.size(); ++j)
                L.c[j] = Rgb{sh9.values[3 * j], sh9.values[3 * j + 1], sh9.values[3 * j + 2]};
            L.c[k] = Rgb{c[0], c[1], c[2]};
            e.sh9 = L;
            later("setting a coefficient", [this, name, e] { session_.editLight(name, e); });
        }
        ImGui::PopID();
    }
    ImGui::TreePop();
}

void App::objectsPanel() {
    if (!ImGui::CollapsingHeader("Virtual parts", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::RadioButton("move objects", tools_.tool == Tool::select)) tools_.tool = Tool::select;
    ImGui::SameLine();
    if (ImGui::RadioButton("add light", tools_.tool == Tool::light)) tools_.tool = Tool::light;
    ImGui::SameLine();
    if (ImGui::RadioButton("add box", tools_.tool == Tool::box)) tools_.tool = Tool::box;
    if (ImGui::RadioButton("add point lamp", tools_.tool == Tool::point)) tools_.tool = Tool::point;
    ImGui::SameLine();
    if (ImGui::RadioButton("remove real objects", tools_.tool == Tool::remove))
        tools_.tool = Tool::remove;
    ImGui::TextDisabled(tools_.tool == Tool::select ? "drag an object over the surface it stands on"
                        : tools_.tool == Tool::light ? "click a surface: a lamp on it"
                        : tools_.tool == Tool::box   ? "click a surface: a box standing on it"
                        : tools_.tool == Tool::point ? "click a surface: a point lamp above it"
                        : tools_.tool == Tool::sun   ? "drag on the image: the sun turns"
                        : tools_.tool == Tool::movePoint
                            ? "click a surface: the lamp goes above it"
                            : "click an object marked removable: it goes");
    const auto& objects = session_.objects();
    int remove = -1;
    for (size_t i = 0; i < objects.size(); ++i) {
        ImGui::PushID(1000 + static_cast<int>(i));
        ImGui::TextUnformatted(objects[i].object.name.c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("remove")) remove = static_cast<int>(i);
        const Rgb& rho = objects[i].object.reflectance;
        float c[3] = {static_cast<float>(rho.r), static_cast<float>(rho.g),
                      static_cast<float>(rho.b)};
        ImGui::ColorEdit3("reflectance", c, ImGuiColorEditFlags_Float);
        if (ImGui::IsItemDeactivatedAfterEdit()) {
            // Below 1: a surface reflects less than it receives (edit_file.h).
            const Rgb r{std::clamp(c[0], 0.0f, 0.99f), std::clamp(c[1], 0.0f, 0.99f),
                        std::clamp(c[2], 0.0f, 0.99f)};
            later("reflectance change",
                  [this, i = static_cast<int>(i), r] { session_.setReflectance(i, r); });
        }
        specularControls(static_cast<int>(i));
        ImGui::PopID();
    }
    if (remove >= 0)
        later("removing the object", [this, remove] { session_.removeObject(remove); });
    // The real objects taken out, each with a button that brings it back.
    std::string restore;
    for (const std::string& name : session_.removedObjects()) {
        ImGui::PushID(name.c_str());
        ImGui::Text("%s (taken out)", name.c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("bring back")) restore = name;
        ImGui::PopID();
    }
    if (!restore.empty())
        later("bringing the object back", [this, restore] { session_.restoreRealObject(restore); });
}

void App::specularControls(int i) {
    // The specular pass (../shared/seeds/000, §6): a Blinn-Phong term on top of the relit
    // image, saved in the session's edit ("specular", docs/scene-format.md).
    const std::optional<Specular>& now = session_.objects()[static_cast<size_t>(i)].object.specular;
    bool on = now.has_value();
    const Specular s = now.value_or(Specular{Rgb{0.5, 0.5, 0.5}, 32});
    float ks[3] = {static_cast<float>(s.ks.r), static_cast<float>(s.ks.g),
                   static_cast<float>(s.ks.b)};
    float shininess = static_cast<float>(s.shininess);
    bool edited = ImGui::Checkbox("specular", &on);
    if (on) {
        ImGui::ColorEdit3("ks", ks, ImGuiColorEditFlags_Float);
        edited = edited || ImGui::IsItemDeactivatedAfterEdit();
        ImGui::DragFloat("shininess", &shininess, 1.0f, 1.0f, 10000.0f, "%.0f",
                         ImGuiSliderFlags_Logarithmic);
        edited = edited || ImGui::IsItemDeactivatedAfterEdit();
    }
    if (!edited) return;
    // ks >= 0 and a shininess > 0 (edit_file.h); the colour picker may go below 0.
    const Specular next{Rgb{std::max(ks[0], 0.0f), std::max(ks[1], 0.0f), std::max(ks[2], 0.0f)},
                        std::clamp(static_cast<double>(shininess), 1.0, 1e4)};
    // Only the overlay changes, unless another object shares the name and the parts are
    // inserted again: in the background either way (a click, not a slider's frames).
    const std::optional<Specular> term = on ? std::optional<Specular>(next) : std::nullopt;
    later("specular change", [this, i, term] { session_.setSpecular(i, term); });
}

void App::lampsPanel() {
    if (!ImGui::CollapsingHeader("Real lamps (scene.json)", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::RadioButton("place real lamps", tools_.tool == Tool::lamp)) tools_.tool = Tool::lamp;
    if (ImGui::DragFloat2("new lamp size (m)", tools_.newLampSize, 0.005f, 0.0f, 10.0f, "%.3f"))
        for (float& side : tools_.newLampSize) side = std::max(0.0f, side);
    // Wrapped: the hints are longer than the panel is wide.
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextDisabled("%s", tools_.movingLamp >= 0
                                  ? "click where the lamp goes"
                                  : "click where a lamp is in the photo: a quad on the surface, "
                                    "facing out (size 0: the scene's lamps' size)");
    ImGui::PopTextWrapPos();
    auto& lamps = session_.placedLamps();
    int remove = -1;
    for (size_t i = 0; i < lamps.size(); ++i) {
        PlacedLamp& l = lamps[i];
        ImGui::PushID(2000 + static_cast<int>(i));
        char name[128];
        std::snprintf(name, sizeof name, "%s", l.name.c_str());
        if (ImGui::InputText("name", name, sizeof name)) l.name = name;
        float size[2] = {static_cast<float>(l.width), static_cast<float>(l.height)};
        if (ImGui::DragFloat2("size (m)", size, 0.005f, 0.01f, 10.0f, "%.3f")) {
            l.width = std::max(0.01f, size[0]);
            l.height = std::max(0.01f, size[1]);
        }
        ImGui::Checkbox("estimate radiance from the photo", &l.estimate);
        if (!l.estimate) {
            float c[3] = {static_cast<float>(l.radiance.r), static_cast<float>(l.radiance.g),
                          static_cast<float>(l.radiance.b)};
            if (ImGui::DragFloat3("radiance", c, 0.05f, 0.0f, 1e4f, "%.2f"))
                l.radiance = Rgb{std::max(0.0f, c[0]), std::max(0.0f, c[1]), std::max(0.0f, c[2])};
        }
        ImGui::Checkbox("on in the photo", &l.onInPhoto);
        if (ImGui::SmallButton("move")) {
            tools_.movingLamp = static_cast<int>(i);
            tools_.tool = Tool::lamp;
        }
        ImGui::SameLine();
        if (ImGui::SmallButton("remove")) remove = static_cast<int>(i);
        ImGui::Separator();
        ImGui::PopID();
    }
    if (remove >= 0) {
        lamps.erase(lamps.begin() + remove);
        tools_.movingLamp = -1;
    }
    if (!lamps.empty() && ImGui::Button("Save lamps into scene.json")) {
        const std::filesystem::path dir = session_.relighting().scene.dir;
        act("saving the lamps", [&] {
            session_.saveLamps(dir);
            status_ = "added the lamps to " + (dir / "scene.json").string() +
                      "; open the scene again to relight with them";
        });
    }
}

/// The real lamps placed, outlined over the photo (the window's coordinates).
void App::drawLamps(const PhotoRect& r) {
    const PreparedImage& p = session_.prepared();
    const Camera& camera = session_.relighting().scene.camera;
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    // Within the photo: a lamp partly out of the picture must not draw over the panel.
    draw->PushClipRect(ImVec2(static_cast<float>(r.x), static_cast<float>(r.y)),
                       ImVec2(static_cast<float>(r.x + r.w), static_cast<float>(r.y + r.h)));
    for (size_t i = 0; i < session_.placedLamps().size(); ++i) {
        std::vector<ImVec2> points;
        for (const Vec3& c : session_.placedLamps()[i].corners()) {
            double u = 0, v = 0, depth = 0;
            if (!camera.project(c, u, v, depth)) break;
            points.emplace_back(static_cast<float>(r.x + (u + 0.5) / p.photo.width * r.w),
                                static_cast<float>(r.y + (v + 0.5) / p.photo.height * r.h));
        }
        if (points.size() != 4) continue;  // behind the camera: nothing to draw
        const ImU32 colour = static_cast<int>(i) == tools_.movingLamp ? IM_COL32(255, 80, 80, 255)
                                                                      : IM_COL32(255, 220, 60, 255);
        draw->AddPolyline(points.data(), 4, colour, ImDrawFlags_Closed, 2.0f);
        draw->AddText(points[3], colour, session_.placedLamps()[i].name.c_str());
    }
    draw->PopClipRect();
}

void App::displayPanel() {
    if (!ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) return;
    int fb = frame_.framebuffer == Framebuffer::float32 ? 0 : 1;
    ImGui::RadioButton("float framebuffer", &fb, 0);
    ImGui::SameLine();
    ImGui::RadioButton("multipass 8-bit", &fb, 1);
    frame_.framebuffer = fb == 0 ? Framebuffer::float32 : Framebuffer::multipass8;
    // The per-pixel display when the preparation measured the light per pixel (--display
    // pixel): drawn on the CPU, the ratio display on the GPU.
    if (!session_.prepared().pixelDirect.empty()) {
        ImGui::Checkbox("per-pixel display (CPU)", &frame_.perPixel);
        // Which one (relight render's --display): the default, 000's ratio map, or Wen et
        // al.'s unoccluded sky.
        constexpr DisplayMode kModes[] = {DisplayMode::pixel, DisplayMode::ratioMap,
                                          DisplayMode::wen};
        int mode = 0;
        for (int i = 0; i < 3; ++i)
            if (kModes[i] == frame_.perPixelMode) mode = i;
        for (int i = 0; i < 3; ++i) {
            if (i > 0) ImGui::SameLine();
            ImGui::RadioButton(displayModeName(kModes[i]), &mode, i);
        }
        frame_.perPixelMode = kModes[mode];
    }
    float exposure = static_cast<float>(frame_.exposure);
    if (ImGui::SliderFloat("exposure (stops)", &exposure, -4.0f, 4.0f, "%.1f"))
        frame_.exposure = exposure;
    int view = 0;
    for (int i = 0; i < static_cast<int>(std::size(kViewKinds)); ++i)
        if (kViewKinds[i] == frame_.view) view = i;
    if (ImGui::BeginCombo("view", viewName(frame_.view))) {
        for (int i = 0; i < static_cast<int>(std::size(kViewKinds)); ++i)
            if (ImGui::Selectable(viewName(kViewKinds[i]), i == view)) frame_.view = kViewKinds[i];
        ImGui::EndCombo();
    }
}

void App::panel() {
    beginPanel();
    lightsPanel();
    objectsPanel();
    lampsPanel();
    displayPanel();
    if (ImGui::CollapsingHeader("Save", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::InputText("file", savePath_, sizeof savePath_);
        if (ImGui::Button("Save edit (relight-edit/1)"))
            act("saving", [&] {
                session_.save(savePath_);
                status_ = std::string("saved ") + savePath_ +
                          "; render it with: relight render <scene> --edit " + savePath_ +
                          " -o out.png";
            });
    }
    if (!status_.empty()) ImGui::TextWrapped("%s", status_.c_str());
    ImGui::End();
}

void App::statsOverlay(const PhotoRect& r) {
    beginOverlay(r);
    const PreparedImage& p = session_.prepared();
    ImGui::Text("frame %.1f ms (%.0f fps)", 1e3 * frameSeconds_,
                static_cast<double>(ImGui::GetIO().Framerate));
    ImGui::Text("update %.1f ms, upload %.1f ms, draw %.1f ms", 1e3 * lastUpdate_,
                1e3 * stats_.upload, 1e3 * stats_.draw);
    ImGui::Text("leaves %d, links %zu, vertices %zu", p.leaves, session_.links(), p.vertexCount());
    ImGui::Text("%dx%d, %s, %d pass%s", p.photo.width, p.photo.height,
                frame_.framebuffer == Framebuffer::float32 ? "float" : "8-bit", stats_.passes,
                stats_.passes == 1 ? "" : "es");
    if (const FrameTimes* t = session_.dynamicTimes())
        ImGui::Text("last part: shafts %.1f, rays %.1f, links %.1f, radiosity %.1f ms",
                    1e3 * t->shafts, 1e3 * t->visibility, 1e3 * t->links, 1e3 * t->radiosity);
    // What is shown: a slider's quick image, or what `relight render` draws of the edit.
    if (session_.exactPending()) ImGui::TextWrapped("%s", session_.stage().c_str());
    if (session_.exactPending() && frame_.drewOnGpu()) ImGui::TextWrapped("drawn on the GPU");
    if (!frame_.gpuNote().empty()) ImGui::TextWrapped("%s", frame_.gpuNote().c_str());
    // A preparation cut short is coarser than render's at the same options: said here too.
    if (p.budgetReached)
        ImGui::TextWrapped(
            "the preparation reached its budget (--time-budget, links or memory): the terminal "
            "lists the coarser fallbacks it took");
    ImGui::End();
}

void App::mouse(const PhotoRect& r) {
    GLFWwindow* w = window_.handle();
    Pointer p;
    p.down = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    glfwGetCursorPos(w, &p.x, &p.y);
    p.onPhoto = !ImGui::GetIO().WantCaptureMouse && r.contains(p.x, p.y);
    tools_.handle(r, p);
    if (!tools_.status.empty()) status_ = std::exchange(tools_.status, {});
}

void App::interact(const PhotoRect& r) {
    // Work in the background ended: its result is drawn below (its error in the panel).
    if (work_.busy()) {
        bool ended = false;
        const bool ok = act(work_.what().c_str(), [&] {
            ended = work_.finish();
            if (ended)
                std::printf(
                    "%s: done in %.2f s, in the background (%d frames drawn meanwhile, the "
                    "longest %.1f ms)\n",
                    work_.what().c_str(), work_.seconds(), busyFrames_, 1e3 * busyLongest_);
        });
        if ((ended || !ok) && scriptRunning_) {
            scriptFailed_ = scriptFailed_ || !ok;
            scriptRunning_ = false;
        }
    }
    if (!work_.busy() && !script_.empty()) {
        ScriptedAction next = std::move(script_.front());
        script_.pop_front();
        inBackground(next.what, [this, run = std::move(next.run)] { run(session_); });
        scriptRunning_ = true;
    }
    if (work_.busy()) {
        busyPanel(r);  // the last image stays in the display's target
        return;
    }
    // Quick frames of a moved sun or lamp in the per-pixel displays only (their direct light
    // per pixel; the ratio display's vertices are solved at each move).
    session_.setQuickMoves(frame_.view == ViewKind::relit && frame_.perPixel);
    panel();
    // The panel's slow action starts now that the panel has read the session to its end;
    // from here the worker alone touches the session until finish(): no mouse this frame,
    // busyPanel() the next ones.
    if (deferred_) {
        Deferred d = std::move(*deferred_);
        deferred_.reset();
        inBackground(std::move(d.what), std::move(d.work));
    } else {
        mouse(r);
    }
}

int App::run() {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_.handle(), true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
    const PreparedImage& p = session_.prepared();
    int lastGeneration = -1, frames = 0;
    while (!glfwWindowShouldClose(window_.handle())) {
        const double t0 = glfwGetTime();
        glfwPollEvents();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        int winW = 0, winH = 0, fbW = 0, fbH = 0;
        glfwGetWindowSize(window_.handle(), &winW, &winH);
        glfwGetFramebufferSize(window_.handle(), &fbW, &fbH);
        const PhotoRect r = photoRect(winW, winH, p.photo.width, p.photo.height);
        interact(r);
        if (!work_.busy()) {
            statsOverlay(r);
            drawLamps(r);
            if (session_.generation() != lastGeneration) {
                lastUpdate_ = session_.updateSeconds();
                lastGeneration = session_.generation();
                lastChange_ = glfwGetTime();
            }
            // A slider's quick image (Session::update) made exact once the hand rests on it.
            if (session_.canSettle() && glfwGetTime() - lastChange_ > kSettleSeconds)
                inBackground("making the image exact", [this] { session_.settle(); });
        }
        if (!work_.busy()) act("drawing", [&] { stats_ = frame_.render(); });
        ImGui::Render();
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fbW, fbH);
        glClearColor(0.12f, 0.12f, 0.12f, 1);
        glClear(GL_COLOR_BUFFER_BIT);
        // Window coordinates (y down) to the framebuffer's pixels (y up; HiDPI scale).
        const double sx = winW > 0 ? static_cast<double>(fbW) / winW : 1;
        const double sy = winH > 0 ? static_cast<double>(fbH) / winH : 1;
        frame_.present(static_cast<int>(std::lround(r.x * sx)),
                       static_cast<int>(std::lround((winH - r.y - r.h) * sy)),
                       static_cast<int>(std::lround(r.w * sx)),
                       static_cast<int>(std::lround(r.h * sy)));
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        // A few frames first: ImGui lays its windows out over the first ones.
        // (The shot waits for the exact image: no work running or to run, nothing left to
        // settle.)
        if (!windowShot_.empty() && !work_.busy() && script_.empty() && !session_.canSettle() &&
            ++frames >= 4) {
            writeImage(windowShot_, readWindow(fbW, fbH));
            std::printf("wrote %s (%dx%d)\n", windowShot_.c_str(), fbW, fbH);
            break;
        }
        glfwSwapBuffers(window_.handle());
        frameSeconds_ = glfwGetTime() - t0;
        if (work_.busy()) {
            ++busyFrames_;
            busyLongest_ = std::max(busyLongest_, frameSeconds_);
        }
    }
    if (work_.busy()) {
        std::printf("waiting for the background work to end: %s\n", work_.what().c_str());
        if (!act(work_.what().c_str(), [&] { work_.wait(); }) && scriptRunning_)
            scriptFailed_ = true;
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    return scriptFailed_ ? 2 : 0;
}

}  // namespace

int runApp(GlWindow& window, Session& session, FrameRenderer& frame, const AppOptions& options) {
    App app(window, session, frame, options);
    return app.run();
}

}  // namespace relight::viewer
