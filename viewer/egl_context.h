// A headless OpenGL 3.3 core context through EGL, on a pbuffer of the image's size: for the
// benchmarks on a machine that has a GPU but no X server its driver can draw for (a compute
// server: NVIDIA's GLX offers no framebuffer configuration on a virtual X server such as
// Xvfb, bench/RESULTS.md 2026-11-27, eighth session). The pbuffer is the default framebuffer,
// so the viewer's renderers draw into it as into a hidden window. libepoxy dispatches the GL
// calls through EGL once the context is current.
#pragma once

#include <string>

#include "viewer/gl_window.h"  // WindowError

namespace relight::viewer {

class EglContext {
  public:
    /// Makes a GL 3.3 core context current on this thread with a width x height pbuffer.
    /// The display is EGL's device platform's first device where the driver offers it
    /// (EGL_EXT_platform_device), else EGL's default display. Throws WindowError.
    EglContext(int width, int height);
    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    /// "NVIDIA H200/PCIe/SSE2, OpenGL 4.6.0 NVIDIA 580.159.04 (EGL, device platform)"
    std::string renderer() const;

  private:
    void* display_ = nullptr;  ///< EGLDisplay
    void* surface_ = nullptr;  ///< EGLSurface
    void* context_ = nullptr;  ///< EGLContext
    std::string platform_;
};

}  // namespace relight::viewer
