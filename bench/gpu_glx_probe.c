/* What a GLX client library offers on a display: the server's and client's GLX strings,
 * the framebuffer configurations and which of them GLFW could take for a window (RGBA, the
 * window bit, double-buffered: glx_context.c's chooseGLXFBConfig), and whether an OpenGL 3.3
 * core context made on a pbuffer of some RGBA configuration gives a renderer. Built and
 * carried by bench/gpu_bundle.sh; bench/gpu_run.sh runs it on the device machine before the
 * bench, so that a failed window ("GLX: Failed to find a suitable GLXFBConfig", seen there
 * on 2026-11-27 with NVIDIA's client library under Xvfb) says what the configurations were.
 *
 *   cc -O1 -o gpu_glx_probe bench/gpu_glx_probe.c -lX11 -lGL
 *   DISPLAY=:99 __GLX_VENDOR_LIBRARY_NAME=nvidia ./gpu_glx_probe
 */
#include <GL/gl.h>
#include <GL/glx.h>
#include <X11/Xlib.h>
#include <stdio.h>

#ifndef GLX_CONTEXT_MAJOR_VERSION_ARB
#define GLX_CONTEXT_MAJOR_VERSION_ARB 0x2091
#define GLX_CONTEXT_MINOR_VERSION_ARB 0x2092
#define GLX_CONTEXT_PROFILE_MASK_ARB 0x9126
#define GLX_CONTEXT_CORE_PROFILE_BIT_ARB 0x00000001
#endif

typedef GLXContext (*CreateContextAttribs)(Display*, GLXFBConfig, GLXContext, Bool, const int*);

static int attrib(Display* d, GLXFBConfig c, int a) {
    int v = -1;
    glXGetFBConfigAttrib(d, c, a, &v);
    return v;
}

static int xerror(Display* d, XErrorEvent* e) {
    (void)d;
    fprintf(stderr, "X error: code %d, request %d.%d\n", e->error_code, e->request_code,
            e->minor_code);
    return 0;
}

/* A 3.3 core context on a pbuffer of `c`: prints the renderer, or why not. */
static void tryContext(Display* d, GLXFBConfig c, const char* what) {
    const CreateContextAttribs create =
        (CreateContextAttribs)glXGetProcAddressARB((const GLubyte*)"glXCreateContextAttribsARB");
    if (!create) {
        printf("%s: no glXCreateContextAttribsARB\n", what);
        return;
    }
    const int ctx[] = {GLX_CONTEXT_MAJOR_VERSION_ARB,
                       3,
                       GLX_CONTEXT_MINOR_VERSION_ARB,
                       3,
                       GLX_CONTEXT_PROFILE_MASK_ARB,
                       GLX_CONTEXT_CORE_PROFILE_BIT_ARB,
                       None};
    GLXContext g = create(d, c, NULL, True, ctx);
    XSync(d, False);
    if (!g) {
        printf("%s: glXCreateContextAttribsARB(3.3 core) failed\n", what);
        return;
    }
    const int pb[] = {GLX_PBUFFER_WIDTH, 64, GLX_PBUFFER_HEIGHT, 64, None};
    GLXPbuffer p = glXCreatePbuffer(d, c, pb);
    XSync(d, False);
    if (!p || !glXMakeContextCurrent(d, p, p, g)) {
        printf("%s: context made, pbuffer %lu, but it cannot be made current\n", what,
               (unsigned long)p);
    } else {
        printf("%s: GL_RENDERER %s, GL_VERSION %s\n", what, (const char*)glGetString(GL_RENDERER),
               (const char*)glGetString(GL_VERSION));
        glXMakeContextCurrent(d, None, None, NULL);
    }
    if (p) glXDestroyPbuffer(d, p);
    glXDestroyContext(d, g);
}

int main(void) {
    XSetErrorHandler(xerror);
    Display* d = XOpenDisplay(NULL);
    if (!d) {
        printf("no display\n");
        return 1;
    }
    const int s = DefaultScreen(d);
    int major = 0, minor = 0;
    printf("GLX extension: %s\n", glXQueryVersion(d, &major, &minor) ? "yes" : "no");
    printf("GLX version %d.%d; server vendor %s; client vendor %s\n", major, minor,
           glXQueryServerString(d, s, GLX_VENDOR), glXGetClientString(d, GLX_VENDOR));
    int n = 0;
    GLXFBConfig* all = glXGetFBConfigs(d, s, &n);
    int rgba = 0, window = 0, usable = 0, pbuffer = 0, firstWindow = -1, firstPbuffer = -1;
    printf("%d GLXFBConfigs; the first 6: id render drawable double r g b a depth stencil visual\n",
           n);
    for (int i = 0; i < n; ++i) {
        const int render = attrib(d, all[i], GLX_RENDER_TYPE);
        const int drawable = attrib(d, all[i], GLX_DRAWABLE_TYPE);
        const int dbl = attrib(d, all[i], GLX_DOUBLEBUFFER);
        if (i < 6)
            printf("  0x%x %#x %#x %d %d %d %d %d %d %d 0x%x\n", attrib(d, all[i], GLX_FBCONFIG_ID),
                   render, drawable, dbl, attrib(d, all[i], GLX_RED_SIZE),
                   attrib(d, all[i], GLX_GREEN_SIZE), attrib(d, all[i], GLX_BLUE_SIZE),
                   attrib(d, all[i], GLX_ALPHA_SIZE), attrib(d, all[i], GLX_DEPTH_SIZE),
                   attrib(d, all[i], GLX_STENCIL_SIZE), attrib(d, all[i], GLX_VISUAL_ID));
        if (render < 0 || !(render & GLX_RGBA_BIT)) continue;
        ++rgba;
        if (drawable >= 0 && (drawable & GLX_PBUFFER_BIT)) {
            ++pbuffer;
            if (firstPbuffer < 0) firstPbuffer = i;
        }
        if (drawable < 0 || !(drawable & GLX_WINDOW_BIT)) continue;
        ++window;
        if (dbl == 1) {
            ++usable;
            if (firstWindow < 0) firstWindow = i;
        }
    }
    printf(
        "RGBA %d, of them with the window bit %d, double-buffered too (what GLFW takes) %d; "
        "RGBA with the pbuffer bit %d\n",
        rgba, window, usable, pbuffer);
    if (firstWindow >= 0) tryContext(d, all[firstWindow], "a window configuration");
    if (firstPbuffer >= 0) tryContext(d, all[firstPbuffer], "a pbuffer configuration");
    if (all) XFree(all);
    XCloseDisplay(d);
    return 0;
}
