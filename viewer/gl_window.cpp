#include "viewer/gl_window.h"

#include <epoxy/gl.h>

#include <cstdlib>

namespace relight::viewer {

namespace {

std::string lastGlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "no reason given";
}

}  // namespace

GlWindow::GlWindow(int width, int height, const std::string& title, bool visible) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland))
        throw WindowError(
            "no display: DISPLAY is not set, so there is no screen to open the window on. Run "
            "relight-viewer in a desktop session, or headless under a virtual X server: "
            "xvfb-run -a relight-viewer ...");
    if (!glfwInit())
        throw WindowError("no display: cannot connect to the X server at DISPLAY=" +
                          std::string(display ? display : "") + " (" + lastGlfwError() + ")");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        const std::string why = lastGlfwError();
        glfwTerminate();
        throw WindowError(
            "no OpenGL 3.3 core context: the display's OpenGL driver cannot give "
            "one (" +
            why + "); relight-viewer needs OpenGL 3.3 (Mesa's llvmpipe will do)");
    }
    glfwMakeContextCurrent(window_);
    if (epoxy_gl_version() < 33) {
        glfwDestroyWindow(window_);
        glfwTerminate();
        throw WindowError("no OpenGL 3.3 core context: the driver gave OpenGL " +
                          std::to_string(epoxy_gl_version() / 10) + "." +
                          std::to_string(epoxy_gl_version() % 10));
    }
    glfwSwapInterval(visible ? 1 : 0);
}

GlWindow::~GlWindow() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

std::string glRenderer() {
    const auto* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return std::string(r ? r : "?") + ", OpenGL " + (v ? v : "?");
}

}  // namespace relight::viewer
