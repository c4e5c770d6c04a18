// One frame of the viewer, without the window's interface: the session's values uploaded to
// the GPU display when they changed, the photo area drawn. The interactive window
// (viewer/app.h), the screenshots and the frame-time benchmark all draw through it, so the
// benchmark times what the window does.
#pragma once

#include <memory>
#include <string>

#include "relight/display/debug_views.h"
#include "viewer/gpu_display.h"
#include "viewer/gpu_moved_light.h"
#include "viewer/session.h"

namespace relight::viewer {

/// What the photo area can show: the relit photo and the debug views.
enum class ViewKind { relit, mesh, B, D, Torig, Tfinal, reflectance, frontier };
inline constexpr ViewKind kViewKinds[] = {
    ViewKind::relit, ViewKind::mesh,   ViewKind::B,           ViewKind::D,
    ViewKind::Torig, ViewKind::Tfinal, ViewKind::reflectance, ViewKind::frontier};
/// "relit", "mesh", "B", "D", "T_orig", "T_final", "reflectance", "frontier"
const char* viewName(ViewKind v);
/// The view named so; throws std::invalid_argument naming the choices otherwise.
ViewKind parseView(const std::string& name);

struct FrameStats {
    double upload = 0;  ///< seconds: the session's values (overlay rays included) to the GPU
    double draw = 0;    ///< seconds: the photo area drawn, glFinish included
    int passes = 1;
};

class FrameRenderer {
  public:
    FrameRenderer(Session& session, GpuRatioDisplay& display);

    ViewKind view = ViewKind::relit;
    Framebuffer framebuffer = Framebuffer::float32;
    double exposure = 0;  ///< stops
    /// The relit view in the per-pixel display (Session::relitPerPixel, drawn on the CPU and
    /// shown as an image) rather than the ratio display on the GPU.
    bool perPixel = false;
    /// Which per-pixel display it is: pixel (relight render's default), ratio-map or wen.
    DisplayMode perPixelMode = DisplayMode::pixel;
    /// In the per-pixel display (DisplayMode::pixel), the frames of a sun or point lamp being
    /// moved (Session::movingLight) drawn on the GPU from its shadow map
    /// (gpu_moved_light.h) rather than measured per pixel on the CPU.
    bool gpuLights = true;
    /// The most GPU memory those frames may take (bytes); 0: half of what the driver says
    /// is free, else half of the process's usable memory (radiosity::usableMemory: Mesa's
    /// llvmpipe holds its textures there). Beyond it, or when the driver runs out, the
    /// frames are the CPU's, and gpuNote() says why.
    size_t gpuMemoryLimit = 0;
    /// Why the moving light's frames are drawn on the CPU although gpuLights is on (a photo
    /// too large for the GPU's memory), or empty.
    const std::string& gpuNote() const { return gpuNote_; }

    /// Uploads what changed since the last call and draws the photo area into the display's
    /// offscreen target. Returns the times.
    FrameStats render();
    /// Draws the photo area into the current framebuffer's viewport (the window).
    void present(int x, int y, int w, int h) { display_.present(x, y, w, h); }
    /// The photo area as last drawn: linear values at the photo's size, exposure included.
    Image read() { return display_.read(); }
    /// Whether the last render() drew anything (values, view or settings changed).
    bool drew() const { return drew_; }
    /// The views that do not depend on the edit (computed once, on first use).
    const DebugViews& debugViews();
    /// Makes the per-pixel display's image of the session as it stands
    /// (Session::relitPerPixel in `mode`), which the next render() shows instead of making it
    /// itself, if nothing changed meanwhile. The window calls it on its worker thread at the
    /// end of the work (viewer/app.cpp): made in the frame after, its shadow rays held that
    /// frame 2 s with a virtual lamp in the room (bench/RESULTS.md, 2026-11-29).
    void prepareImage(DisplayMode mode);

    /// Whether the last render() drew the moving light's frame on the GPU (gpuLights).
    bool drewOnGpu() const { return drewOnGpu_; }

  private:
    /// The per-pixel image: prepareImage()'s when it is of this state, else made now.
    Image relitImage();
    /// The moving light's frame on the GPU (gpuLights) into the display's float target;
    /// false, drawing nothing, where the session has no such frame.
    bool drawMovedLight(float gain, FrameStats& s);
    /// Remembers what the frame just drawn shows (render() draws again when it changes);
    /// returns its times.
    FrameStats drawn(const FrameStats& s);

    Session& session_;
    GpuRatioDisplay& display_;
    std::unique_ptr<DebugViews> views_;
    int generation_ = -1;
    ViewKind lastView_ = ViewKind::relit;
    Framebuffer lastFramebuffer_ = Framebuffer::float32;
    double lastExposure_ = 0;
    bool lastPerPixel_ = false;
    DisplayMode lastPerPixelMode_ = DisplayMode::pixel;
    bool drew_ = false, drewOnGpu_ = false;
    std::unique_ptr<GpuMovedLight> moved_;
    int movedEpoch_ = -1;      ///< the session's movingEpoch() whose frame moved_ holds
    bool movedValid_ = false;  ///< whether that epoch has a frame
    std::string gpuNote_;
    /// Whether the GPU frames of the photo fit in gpuMemoryLimit (else gpuNote_ says so).
    bool movedFramesFit();
    FrameStats last_;
    Image prepared_;               ///< prepareImage()'s
    int preparedGeneration_ = -1;  ///< the session's generation it shows; -1: none
    DisplayMode preparedMode_ = DisplayMode::pixel;
};

}  // namespace relight::viewer
