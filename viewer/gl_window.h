// The viewer's window and OpenGL 3.3 core context (GLFW, libepoxy), with clear messages
// for what a user can get wrong: no display (DISPLAY unset, no X server), no OpenGL 3.3
// core context (an old driver, a remote session without GLX).
#pragma once

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <stdexcept>
#include <string>

namespace relight::viewer {

/// A failure to open the window or its context, with a message for the user.
struct WindowError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The current context's renderer and version: "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL
/// 4.5 (Core Profile) Mesa 22.3.6" ("?" for what the driver does not say).
std::string glRenderer();

class GlWindow {
  public:
    /// Opens a window (hidden when !visible: screenshots and benchmarks) with an OpenGL 3.3
    /// core context, current on this thread. Throws WindowError.
    GlWindow(int width, int height, const std::string& title, bool visible);
    ~GlWindow();
    GlWindow(const GlWindow&) = delete;
    GlWindow& operator=(const GlWindow&) = delete;

    GLFWwindow* handle() const { return window_; }
    std::string renderer() const { return glRenderer(); }  ///< of its context (current)

  private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace relight::viewer
