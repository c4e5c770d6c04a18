#include "viewer/egl_context.h"

#include "viewer/gl_window.h"  // glRenderer

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <vector>

namespace relight::viewer {

namespace {

/// EGL's device platform's first device (a GPU without a display server), or no display.
EGLDisplay deviceDisplay() {
    if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device")) return EGL_NO_DISPLAY;
    const auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (!queryDevices) return EGL_NO_DISPLAY;
    EGLint count = 0;
    std::vector<EGLDeviceEXT> devices(8);
    if (!queryDevices(static_cast<EGLint>(devices.size()), devices.data(), &count) || count < 1)
        return EGL_NO_DISPLAY;
    return eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
}

std::string eglError(const char* what) {
    char code[32];
    std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
    return std::string(what) + " failed (EGL error " + code + ")";
}

}  // namespace

EglContext::EglContext(int width, int height) {
    EGLDisplay display = deviceDisplay();
    platform_ = "device platform";
    if (display == EGL_NO_DISPLAY) {
        display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        platform_ = "default display";
    }
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor))
        throw WindowError("no EGL display: " + eglError("eglInitialize"));
    display_ = display;
    const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                    EGL_PBUFFER_BIT,
                                    EGL_RENDERABLE_TYPE,
                                    EGL_OPENGL_BIT,
                                    EGL_RED_SIZE,
                                    8,
                                    EGL_GREEN_SIZE,
                                    8,
                                    EGL_BLUE_SIZE,
                                    8,
                                    EGL_ALPHA_SIZE,
                                    8,
                                    EGL_DEPTH_SIZE,
                                    24,
                                    EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display, configAttribs, &config, 1, &configs) || configs < 1)
        throw WindowError("no EGL configuration with an RGBA8 pbuffer for OpenGL: " +
                          eglError("eglChooseConfig"));
    const EGLint surfaceAttribs[] = {EGL_WIDTH, width, EGL_HEIGHT, height, EGL_NONE};
    surface_ = eglCreatePbufferSurface(display, config, surfaceAttribs);
    if (surface_ == EGL_NO_SURFACE) throw WindowError(eglError("eglCreatePbufferSurface"));
    if (!eglBindAPI(EGL_OPENGL_API)) throw WindowError(eglError("eglBindAPI(OpenGL)"));
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     3,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_NONE};
    context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT)
        throw WindowError("no OpenGL 3.3 core context through EGL: " +
                          eglError("eglCreateContext"));
    if (!eglMakeCurrent(display, surface_, surface_, context_))
        throw WindowError(eglError("eglMakeCurrent"));
    if (epoxy_gl_version() < 33)
        throw WindowError("no OpenGL 3.3 core context: EGL's driver gave OpenGL " +
                          std::to_string(epoxy_gl_version() / 10) + "." +
                          std::to_string(epoxy_gl_version() % 10));
}

EglContext::~EglContext() {
    if (!display_) return;
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display_, context_);
    if (surface_) eglDestroySurface(display_, surface_);
    eglTerminate(display_);
}

std::string EglContext::renderer() const {
    return glRenderer() + " (EGL, " + platform_ + ")";
}

}  // namespace relight::viewer
