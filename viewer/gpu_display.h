// The ratio display on the GPU (Loscos, Drettakis & Robert 2000, Eq. (3), §5.3).
//
// Each pixel of the photo texture T is modulated by the display ratio B/D of the leaf
// vertices that shade it. Which vertices, and with what interpolation weights, is the
// display map of the preparation (relight/display/ratio_display.h): the item buffer's samples per
// pixel, each interpolated between the corners of its leaf element. The map is uploaded
// once into texture buffers; a frame uploads only the per-vertex ratios (one RGBA float per
// vertex), the lights' radiances and the virtual parts' overlay box, and a fragment shader
// does per pixel what renderRatio() does on the CPU:
//   out = max(0, E_now + A * (U + sum_v w_v r_v)),  A = T_rest / (1 - f_emitters)
//   out = realShare * out + added                     (virtual parts,
//   relight/dynamic/dynamic_relighting.h)
// so the viewer's image is `relight render`'s up to float rounding.
//
// Two framebuffers, as the issue and the paper ask:
//  - float: one pass into an RGBA32F target; ratios above 1 need nothing special;
//  - multipass, 8 bits: the paper's brightening for ratios above 1 (§5.3, Fig. 19). An 8-bit
//    target holds [0, 1], so pass k = 0 .. n-1, n = ceil(max ratio), draws the texture
//    modulated by the per-vertex colour clamp(r_v - k, 0, 1) (the paper's glColor, clamped
//    per vertex and then interpolated) with additive blending; the passes sum to T r up to
//    8-bit rounding (relight/display/multipass.h). One pass when no ratio exceeds 1. The target and
//    the 8-bit photo texture are sRGB-encoded (GL_SRGB8_ALPHA8): blending happens on linear
//    values and the 8 bits are spent as in the PNG the screenshot writes, so the quantization
//    is the PNG's and not a linear 8-bit posterization of the shadows.
// The emitting-face term and the overlay's added radiance are drawn in pass 0 only: they
// are non-negative, so the framebuffer's clip at 1 is the final image's clip anyway.
//
// All methods need the OpenGL 3.3 context current on the calling thread.
#pragma once

#include <epoxy/gl.h>

#include <span>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/dynamic/dynamic_relighting.h"
#include "relight/io/image.h"
#include "relight/prepared.h"

namespace relight::viewer {

using radiosity::Rgb;

enum class Framebuffer { float32, multipass8 };

/// What the photo area shows.
enum class View {
    relit,  ///< the relit photo: T modulated by the display ratio (setVertexValues: k H/D)
    B,      ///< bFactor * sum_v w_v H(v): the radiosity as radiance (setVertexValues: H)
    image,  ///< a fixed image (setImage): the other debug views
};

class GpuRatioDisplay {
  public:
    /// Uploads the display map, the photo and the emitting faces' radiances in the photo.
    explicit GpuRatioDisplay(const PreparedImage& p);
    ~GpuRatioDisplay();
    GpuRatioDisplay(const GpuRatioDisplay&) = delete;
    GpuRatioDisplay& operator=(const GpuRatioDisplay&) = delete;

    int width() const { return width_; }
    int height() const { return height_; }

    /// One value per leaf vertex: the display ratio for View::relit, H for View::B.
    void setVertexValues(std::span<const Rgb> values);
    /// The real lights' radiances now (their emitting faces show them).
    void setRadiance(std::span<const Rgb> radianceNow);
    /// The virtual parts' box (relight/dynamic/dynamic_relighting.h); the previous box is cleared.
    void setOverlay(const VirtualOverlay& overlay);
    /// The per-pixel factor of View::B (DebugViews::bFactor).
    void setBFactor(const Image& factor);
    /// The fixed image of View::image (linear values).
    void setImage(const Image& image);

    /// Draws the photo area into the offscreen target at the photo's size. `gain` scales
    /// the values (exposure 2^stops; for the B view also its display scale). Returns the
    /// passes drawn (1 with the float target).
    int draw(View view, Framebuffer fb, float gain);
    /// Binds the float target at the photo's size, viewport set, for a pass that another
    /// program draws (a moved light's frames, gpu_moved_light.h); read() and present() then
    /// show what it drew.
    void bindFloatTarget();
    /// Passes the multipass target needs for the current values and gain.
    int passesNeeded(float gain) const;

    /// The last draw's photo area, linear values, rows from the top (exposure included).
    Image read();
    /// Draws the last draw's photo area into the current framebuffer's viewport, sRGB
    /// encoded and clipped to [0, 1] (the default framebuffer of the window).
    void present(int x, int y, int w, int h);

  private:
    void uploadImageTexture(GLuint tex, const Image& img, float alpha);

    int width_ = 0, height_ = 0, lights_ = 0;
    float maxValue_ = 0;  ///< largest value of a shown vertex (passes of the multipass target)
    /// Per leaf vertex: whether some pixel shows it. A vertex no pixel shows must not add
    /// passes (one under a box, with D = 0, reaches ratios of 17 while the shown ones stay
    /// below 3: bench/viewer_frames).
    std::vector<char> shown_;
    bool anyUnshaded_ = false;
    GLuint vao_ = 0, program_ = 0, presentProgram_ = 0;
    // Texture buffers (buffer, texture) of the display map and the per-frame values.
    GLuint pixelStartBuf_ = 0, pixelStartTex_ = 0;  ///< per pixel + 1: entry, emitter start
    GLuint vertexBuf_ = 0, vertexTex_ = 0;          ///< per entry: leaf vertex
    GLuint weightBuf_ = 0, weightTex_ = 0;          ///< per entry: weight
    GLuint emitterLightBuf_ = 0, emitterLightTex_ = 0;
    GLuint emitterFracBuf_ = 0, emitterFracTex_ = 0;
    GLuint valueBuf_ = 0, valueTex_ = 0;        ///< per vertex: RGBA32F
    GLuint radianceBuf_ = 0, radianceTex_ = 0;  ///< per real light: RGBA32F
    // 2D textures at the photo's size.
    GLuint photoTex_ = 0;    ///< RGBA32F: A, unshaded fraction U
    GLuint photo8Tex_ = 0;   ///< SRGB8_ALPHA8: clamp(T_rest, 0, 1)
    GLuint overlayTex_ = 0;  ///< RGBA32F: added, realShare
    GLuint factorTex_ = 0, imageTex_ = 0;
    // Offscreen targets.
    GLuint floatFbo_ = 0, floatTex_ = 0, byteFbo_ = 0, byteTex_ = 0, readFbo_ = 0, readTex_ = 0;
    GLuint lastTex_ = 0;  ///< colour texture of the last draw
    VirtualOverlay lastOverlay_;
};

}  // namespace relight::viewer
