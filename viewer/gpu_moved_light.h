// The frames of a sun, point lamp or quad lamp being moved, drawn on the GPU (the ratio-map paper,
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
//   a quad lamp:   pi F(x -> face) times the mean visibility of its 4 points
//                  (F by Lambert's contour integral, as radiosity::pointToPolygon)
// (radiosity::ShadowSource), the visibility from shadow maps of the frame's blockers (the
// lamp's own face not among them):
//   a point lamp:  a cube map of the distance to the lamp, kCubeSide texels a face;
//   a sun:         an orthographic map of the distance along the sun's direction over the
//                  blockers' bounding sphere, kSunSide texels a side;
//   a quad lamp:   a cube map per point of ShadowSource::facePoints (the centres of its
//                  2 x 2 cells), kFaceCubeSide texels a face: a penumbra in five steps.
// A quad lamp's face is drawn too, where it is at each frame: over the share of each pixel's
// k x k camera samples whose rays meet it before what the pixel's centre shows, its radiance
// on its front (MovedLightFrame::camera, surface; relight/dynamic/quick_light.h,
// faceCoverage).
// A receiver is lit when its point, moved 1.5 texels along its normal, is no farther from
// the light than the map's nearest blocker plus two texels (acne and peter-panning both
// within about two texels of the map).
//
// What differs from the CPU's quick frame (one ray per pixel, radiosity::Emitter::
// unitIrradiance): a shadow's edge is where the map's texels put it, to about two texels,
// and a blocker thinner than that may be missed; a quad lamp's penumbra is the mean of four
// points' shadows where the CPU's is one ray's 0 or 1. The image at rest is the exact one as
// before (Session::settle).
//
// All methods need the OpenGL 3.3 context current on the calling thread.
#pragma once

#include <epoxy/gl.h>

#include <glm/vec3.hpp>

#include <memory>
#include <vector>

#include "radiosity/emitter.h"
#include "relight/dynamic/dynamic_relighting.h"

namespace relight::viewer {

class GpuMovedLight {
  public:
    static constexpr int kCubeSide = 512;  ///< texels per side of a point lamp's cube face
    static constexpr int kSunSide = 1024;  ///< texels per side of a sun's map
    /// A face's cubes: one per point (ShadowSource::facePoints), texels per side of each face.
    static constexpr int kFacePoints = radiosity::ShadowSource::kFacePoints;
    static constexpr int kFaceCubeSide = 256;

    /// For a photo of `width` x `height` pixels.
    GpuMovedLight(int width, int height);
    /// The GPU memory a photo of `pixels` pixels needs (bytes): 160 a pixel for the
    /// receivers, the terms and the pooled reflectance per radius, and the shadow maps.
    static size_t bytesNeeded(size_t pixels);
    /// How much of it the OpenGL driver says is free (bytes; GL_NVX_gpu_memory_info or
    /// GL_ATI_meminfo), or 0 where it does not say (Mesa's llvmpipe, which holds textures in
    /// the process's memory, among others).
    static size_t driverFreeMemory();
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
    /// The cube of distances to `at` (the shadow program bound) into the 6 `fbos`.
    void renderCube(const glm::vec3& at, const GLuint* fbos, int side);
    /// A face's corners, normal and points (ShadowSource::Kind::face; nothing otherwise).
    void setFaceUniforms(const radiosity::ShadowSource& source);
    void shadowPass(GLuint fbo, const float* viewProj, int side);

    int width_ = 0, height_ = 0;
    bool hasFrame_ = false;
    GLuint vao_ = 0, program_ = 0, shadowProgram_ = 0;
    GLuint blockerVao_ = 0, blockerBuf_ = 0;
    GLsizei blockerVertices_ = 0;
    radiosity::Vec3 centre_{0, 0, 0};  ///< the blockers' bounding sphere
    double radius_ = 1;
    // Per pixel, at the photo's size: receiver point and normal; the terms.
    GLuint surfaceTex_ = 0, pointTex_ = 0, normalTex_ = 0, restTex_ = 0, rhoTex_ = 0,
           rhoPoolTex_ = 0;
    GLuint photoLightTex_ = 0, scaleTex_ = 0, offsetTex_ = 0, pooledTex_ = 0;
    bool pooled_ = false;
    std::shared_ptr<const std::vector<float>> pooledData_;  ///< what pooledTex_ holds
    float radiance_[3] = {0, 0, 0}, delta_[3] = {0, 0, 0}, eye_[3] = {0, 0, 0};
    float worldFromCamera_[9] = {}, intrinsics_[4] = {1, 1, 0, 0};
    int samplesPerSide_ = 1;
    // Shadow maps: a cube of distances (point lamps), a square of distances (suns).
    GLuint cubeTex_ = 0, cubeDepth_ = 0, cubeFbo_[6] = {};
    GLuint sunTex_ = 0, sunDepth_ = 0, sunFbo_ = 0;
    GLuint faceTex_[kFacePoints] = {}, faceDepth_ = 0, faceFbo_[kFacePoints][6] = {};
    float sunViewProj_[16] = {};
};

}  // namespace relight::viewer
