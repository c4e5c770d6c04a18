#include "viewer/frame.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "radiosity/machine_memory.h"
#include "radiosity/stopwatch.h"

namespace relight::viewer {

using radiosity::Clock;
using radiosity::secondsSince;

const char* viewName(ViewKind v) {
    switch (v) {
        case ViewKind::relit:
            return "relit";
        case ViewKind::mesh:
            return "mesh";
        case ViewKind::B:
            return "B";
        case ViewKind::D:
            return "D";
        case ViewKind::Torig:
            return "T_orig";
        case ViewKind::Tfinal:
            return "T_final";
        case ViewKind::reflectance:
            return "reflectance";
        case ViewKind::frontier:
            return "frontier";
    }
    return "?";
}

ViewKind parseView(const std::string& name) {
    std::string all;
    for (ViewKind v : kViewKinds) {
        if (name == viewName(v)) return v;
        all += (all.empty() ? "" : ", ") + std::string(viewName(v));
    }
    throw std::invalid_argument("unknown view \"" + name + "\" (the views: " + all + ")");
}

FrameRenderer::FrameRenderer(Session& session, GpuRatioDisplay& display)
    : session_(session), display_(display) {}

const DebugViews& FrameRenderer::debugViews() {
    // The views of the photo's own lighting: all but B do not depend on the edit (B is
    // drawn on the GPU from the vertex irradiance with their bFactor).
    if (!views_)
        views_ = std::make_unique<DebugViews>(
            computeDebugViews(session_.relighting(), session_.prepared().photoRadiance));
    return *views_;
}

void FrameRenderer::prepareImage(DisplayMode mode) {
    prepared_ = session_.relitPerPixel(mode);
    preparedGeneration_ = session_.generation();
    preparedMode_ = mode;
}

Image FrameRenderer::relitImage() {
    const bool current =
        preparedGeneration_ == session_.generation() && preparedMode_ == perPixelMode;
    preparedGeneration_ = -1;  // shown once; a later state is made again
    if (current) return std::move(prepared_);
    return session_.relitPerPixel(perPixelMode);
}

bool FrameRenderer::movedFramesFit() {
    const size_t pixels =
        static_cast<size_t>(display_.width()) * static_cast<size_t>(display_.height());
    const size_t need = GpuMovedLight::bytesNeeded(pixels);
    size_t limit = gpuMemoryLimit;
    if (limit == 0) limit = GpuMovedLight::driverFreeMemory() / 2;
    if (limit == 0) limit = radiosity::usableMemory() / 2;
    GLint side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &side);
    if (need <= limit && display_.width() <= side && display_.height() <= side) return true;
    if (gpuNote_.empty()) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "a moved light's frames are drawn on the CPU: on the GPU a %dx%d photo "
                      "needs %.0f MB, and %.0f MB (textures of %d pixels a side) are at hand",
                      display_.width(), display_.height(), 1e-6 * static_cast<double>(need),
                      1e-6 * static_cast<double>(limit), side);
        gpuNote_ = text;
        std::fprintf(stderr, "relight-viewer: %s\n", gpuNote_.c_str());
    }
    return false;
}

bool FrameRenderer::drawMovedLight(float gain, FrameStats& s) {
    const std::optional<radiosity::ShadowSource> source = session_.movingSource();
    if (!source) return false;
    const auto t0 = Clock::now();
    if (movedEpoch_ != session_.movingEpoch()) {
        // Once per drag: everything but the light's direct light, and what blocks it.
        movedEpoch_ = session_.movingEpoch();
        movedValid_ = false;
        if (!movedFramesFit()) return false;
        const std::optional<MovedLightFrame> f = session_.movedLightFrame();
        if (f) {
            while (glGetError() != GL_NO_ERROR) {
            }
            if (!moved_)
                moved_ = std::make_unique<GpuMovedLight>(display_.width(), display_.height());
            moved_->setFrame(*f);
            movedValid_ = glGetError() != GL_OUT_OF_MEMORY;
            if (!movedValid_) {  // the driver ran out: the CPU's frames, its memory given back
                moved_.reset();
                gpuNote_ = "a moved light's frames are drawn on the CPU: the GPU ran out of memory";
                std::fprintf(stderr, "relight-viewer: %s\n", gpuNote_.c_str());
            }
        }
    }
    if (!movedValid_) return false;
    glFinish();
    s.upload = secondsSince(t0);
    const auto t1 = Clock::now();
    display_.bindFloatTarget();
    moved_->draw(*source, gain);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glFinish();
    s.draw = secondsSince(t1);
    return true;
}

FrameStats FrameRenderer::render() {
    const bool valuesChanged = session_.generation() != generation_;
    const bool viewChanged = view != lastView_ || generation_ < 0;
    const bool modeChanged = perPixel != lastPerPixel_ || perPixelMode != lastPerPixelMode_;
    drew_ = valuesChanged || viewChanged || modeChanged || framebuffer != lastFramebuffer_ ||
            exposure != lastExposure_;
    if (!drew_) return last_;
    FrameStats s;
    const auto t0 = Clock::now();
    double gain = std::exp2(exposure);
    const bool cpuRelit = view == ViewKind::relit && perPixel;
    drewOnGpu_ = cpuRelit && gpuLights && perPixelMode == DisplayMode::pixel &&
                 session_.movingLight() >= 0 && drawMovedLight(static_cast<float>(gain), s);
    if (drewOnGpu_) return drawn(s);
    if (cpuRelit) {
        if (valuesChanged || viewChanged || modeChanged) display_.setImage(relitImage());
    } else if (view == ViewKind::relit || view == ViewKind::B) {
        if (valuesChanged || viewChanged) {
            display_.setVertexValues(view == ViewKind::B ? session_.vertexIrradiance()
                                                         : session_.vertexRatios());
            display_.setRadiance(session_.realRadiance());
        }
        if (valuesChanged) display_.setOverlay(session_.overlay());
        if (view == ViewKind::B) {
            if (viewChanged) display_.setBFactor(debugViews().bFactor);
            gain *= debugViews().bdScale;
        }
    } else if (viewChanged || modeChanged) {
        const DebugViews& v = debugViews();
        const Image* img = nullptr;
        switch (view) {
            case ViewKind::mesh:
                img = &v.mesh;
                break;
            case ViewKind::D:
                img = &v.D;
                break;
            case ViewKind::Torig:
                img = &v.Torig;
                break;
            case ViewKind::Tfinal:
                img = v.Tfinal.width > 0 ? &v.Tfinal : &v.Torig;
                break;
            case ViewKind::reflectance:
                img = &v.reflectance;
                break;
            case ViewKind::frontier:
                img = v.frontier.width > 0 ? &v.frontier : &v.mesh;
                break;
            default:
                break;
        }
        if (img) display_.setImage(*img);
    }
    if (view == ViewKind::D) gain *= debugViews().bdScale;
    glFinish();
    s.upload = secondsSince(t0);
    const auto t1 = Clock::now();
    const View gpuView = cpuRelit                  ? View::image
                         : view == ViewKind::relit ? View::relit
                         : view == ViewKind::B     ? View::B
                                                   : View::image;
    s.passes = display_.draw(gpuView, framebuffer, static_cast<float>(gain));
    glFinish();
    s.draw = secondsSince(t1);
    return drawn(s);
}

FrameStats FrameRenderer::drawn(const FrameStats& s) {
    generation_ = session_.generation();
    lastView_ = view;
    lastFramebuffer_ = framebuffer;
    lastExposure_ = exposure;
    lastPerPixel_ = perPixel;
    lastPerPixelMode_ = perPixelMode;
    last_ = s;
    return s;
}

}  // namespace relight::viewer
