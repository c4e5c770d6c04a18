// The frames of a sun or point lamp being moved, drawn on the GPU (the ratio-map paper,
// ../shared/seeds/000, §4: the new light rendered per frame by the graphics hardware, with
// its cast shadows; issue 32: "every lamp's direct light per pixel is computed on the GPU
// each frame").
//
// While the light moves, everything in the per-pixel display but its direct light stays as
// it is. DynamicRelighting::movedLightFrame (relight/dynamic/dynamic_relighting.h) gives the
// image as a function of that light alone:
//   image = scale * out(g) + offset,   out(g) = max(0, R (max(rest + L_m g, 0) + delta))
// with R the pixel's reflectance, pooled where the light brightens the photo much
// (relight/pipeline/pixel_light.h, evalPixelLightTerms). It is uploaded once per drag
// (setFrame). Each frame then only renders the light's shadow map and one pass over the
// photo's pixels: g, the light's unit irradiance at the pixel's receiver (the camera sample
// the CPU's quick frames light, quickReceivers), is
//   a point lamp:  max(0, n.v) / |v|^3 times its visibility,  v = lamp - x
//   a sun:         max(0, n.s) times its visibility            (its disc's centre)
// (radiosity::ShadowSource), the visibility from a shadow map of the frame's blockers:
//   a point lamp:  a cube map of the distance to the lamp, kCubeSide texels a face;
//   a sun:         an orthographic map of the distance along the sun's direction over the
//                  blockers' bounding sphere, kSunSide texels a side.
// A receiver is lit when its point, moved 1.5 texels along its normal, is no farther from
// the light than the map's nearest blocker plus two texels (acne and peter-panning both
// within about two texels of the map).
//
// What differs from the CPU's quick frame (one ray per pixel, radiosity::Emitter::
// unitIrradiance): a shadow's edge is where the map's texels put it, to about two texels,
// and a blocker thinner than that may be missed. The image at rest is the exact one as
// before (Session::settle).
//
// All methods need the OpenGL 3.3 context current on the calling thread.
#pragma once

#include <epoxy/gl.h>

#include <memory>
#include <vector>

#include "radiosity/emitter.h"
#include "relight/dynamic/dynamic_relighting.h"

namespace relight::viewer {

class GpuMovedLight {
  public:
    static constexpr int kCubeSide = 512;  ///< texels per side of a point lamp's cube face
    static constexpr int kSunSide = 1024;  ///< texels per side of a sun's map

    /// For a photo of `width` x `height` pixels.
    GpuMovedLight(int width, int height);
    ~GpuMovedLight();
    GpuMovedLight(const GpuMovedLight&) = delete;
    GpuMovedLight& operator=(const GpuMovedLight&) = delete;

    /// Uploads a frame's terms, receivers and blockers (once per drag). Throws
    /// std::invalid_argument for a frame of another size than the photo.
    void setFrame(const MovedLightFrame& frame);
    bool hasFrame() const { return hasFrame_; }
    /// Draws the frame with the light at `source` into the bound framebuffer, whose viewport
    /// must be the photo's size (GpuRatioDisplay::bindFloatTarget), values times `gain`.
    void draw(const radiosity::ShadowSource& source, float gain);

  private:
    /// The shadow map of the blockers seen from `source`; sets the uniforms that read it.
    void renderShadowMap(const radiosity::ShadowSource& source);
    void shadowPass(GLuint fbo, const float* viewProj, int side);

    int width_ = 0, height_ = 0;
    bool hasFrame_ = false;
    GLuint vao_ = 0, program_ = 0, shadowProgram_ = 0;
    GLuint blockerVao_ = 0, blockerBuf_ = 0;
    GLsizei blockerVertices_ = 0;
    radiosity::Vec3 centre_{0, 0, 0};  ///< the blockers' bounding sphere
    double radius_ = 1;
    // Per pixel, at the photo's size: receiver point and normal; the terms.
    GLuint pointTex_ = 0, normalTex_ = 0, restTex_ = 0, rhoTex_ = 0, rhoPoolTex_ = 0;
    GLuint photoLightTex_ = 0, scaleTex_ = 0, offsetTex_ = 0, pooledTex_ = 0;
    bool pooled_ = false;
    std::shared_ptr<const std::vector<float>> pooledData_;  ///< what pooledTex_ holds
    float radiance_[3] = {0, 0, 0}, delta_[3] = {0, 0, 0};
    // Shadow maps: a cube of distances (point lamps), a square of distances (suns).
    GLuint cubeTex_ = 0, cubeDepth_ = 0, cubeFbo_[6] = {};
    GLuint sunTex_ = 0, sunDepth_ = 0, sunFbo_ = 0;
    float sunViewProj_[16] = {};
};

}  // namespace relight::viewer
