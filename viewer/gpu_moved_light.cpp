#include "viewer/gpu_moved_light.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <stdexcept>
#include <vector>

#include "relight/pipeline/pixel_light.h"
#include "viewer/gl_util.h"

namespace relight::viewer {

namespace {

// The blockers seen from the light: each fragment keeps its distance to the light (a point
// lamp) or to the plane beyond the blockers' sphere on the sun's side (a sun), the nearest
// by the depth test.
const char* kShadowVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
uniform mat4 viewProj;
out vec3 world;
void main() {
    world = position;
    gl_Position = viewProj * vec4(position, 1.0);
}
)";

const char* kShadowFragment = R"(#version 330 core
uniform int kind;       // 0 point lamp, 1 sun
uniform vec3 at;        // the lamp, or the unit direction towards the sun
uniform vec3 centre;    // the blockers' bounding sphere
uniform float radius;
in vec3 world;
out float distance;
void main() {
    distance = kind == 0 ? length(world - at) : radius - dot(world - centre, at);
}
)";

// The frame (gpu_moved_light.h): g from the light and its shadow map, then
// evalPixelLightTerms (relight/pipeline/pixel_light.cpp) per channel, then scale and offset.
const char* kFrameFragment = R"(#version 330 core
uniform sampler2D receiverPoint;
uniform sampler2D surface;          // a face: the first point the pixel's ray meets
uniform sampler2D receiverNormal;   // 0: no receiver (g = 0)
uniform sampler2D rest;             // H_now with the light's direct light at 0
uniform sampler2D rho;              // T / (max(H_photo, 0) + delta)
uniform sampler2D rhoPool;
uniform sampler2D photoLight;       // lum(H_photo) where the pool applies, else 0
uniform sampler2D scale;
uniform sampler2D offset;
uniform sampler2DArray pooled;      // per radius from poolRadius
uniform samplerCube cube;
uniform sampler2D sunMap;
uniform samplerCube face0;          // a face's cubes, one per point of ShadowSource::facePoints
uniform samplerCube face1;
uniform samplerCube face2;
uniform samplerCube face3;
uniform int height;
uniform int kind;                   // 0 point lamp, 1 sun, 2 face
uniform vec3 at;
uniform vec3 centre;
uniform float radius;
uniform mat4 sunViewProj;
uniform float cubeTexel;            // radians per cube texel
uniform float sunTexel;             // metres per sun texel
uniform float faceTexel;            // radians per texel of a face's cubes
uniform vec3 facePoint[4];
uniform vec3 corner[4];             // the face, counter-clockwise seen from its front
uniform int cornerCount;
uniform vec3 faceNormal;
uniform vec3 eye;                   // the camera's centre (a face is drawn where it is)
uniform mat3 worldFromCamera;       // R^T of the photo's camera
uniform vec4 intrinsics;            // fx, fy, cx, cy
uniform int samplesPerSide;         // the overlay's k x k samples of a pixel
uniform vec3 radiance;              // L_m
uniform vec3 delta;
uniform int havePooled;
uniform float poolAbove;
uniform int poolRadius;
uniform int maxPoolRadius;
uniform float gain;
out vec4 color;

const float PI = 3.14159265358979;

// Whether p (normal n) sees the point s, from s's cube of distances.
float cubeVisible(samplerCube c, vec3 s, vec3 p, vec3 n, float texelAngle) {
    float texel = texelAngle * length(p - s);
    vec3 q = p + n * (1.5 * texel);
    return length(q - s) - 2.0 * texel <= texture(c, q - s).r ? 1.0 : 0.0;
}

// One edge's term of Lambert's contour integral (radiosity/detail/form_factor.cpp).
float edgeTerm(vec3 a, vec3 b, vec3 n) {
    vec3 c = cross(b, a);
    float cl = length(c);
    if (cl <= 1e-30) return 0.0;
    return atan(cl, dot(a, b)) * dot(n, c) / cl;
}

// F(x -> face), one-sided, the face clipped to x's hemisphere: pointToPolygon
// (radiosity/detail/form_factor.h) in float, its clipping offset 1e-6 of the configuration's
// size (float's rounding, where the CPU takes 1e-12).
float faceFormFactor(vec3 x, vec3 n) {
    float size = 0.0;
    for (int i = 0; i < 4; ++i) {
        if (i >= cornerCount) break;
        vec3 r = abs(corner[i] - x);
        size = max(size, max(r.x, max(r.y, r.z)));
    }
    float eps = 1e-6 * size;
    if (!(dot(faceNormal, x - corner[0]) > eps)) return 0.0;
    float sum = 0.0;
    vec3 first = vec3(0.0), prev = vec3(0.0);
    int k = 0;
    vec3 a = corner[cornerCount - 1] - x;
    float ha = dot(n, a) - eps;
    for (int i = 0; i < 4; ++i) {
        if (i >= cornerCount) break;
        vec3 b = corner[i] - x;
        float hb = dot(n, b) - eps;
        for (int e = 0; e < 2; ++e) {  // the crossing, then b: Sutherland-Hodgman
            bool emit = e == 0 ? (ha > 0.0) != (hb > 0.0) : hb > 0.0;
            if (!emit) continue;
            vec3 m = e == 0 ? a + ha / (ha - hb) * (b - a) : b;
            if (k == 0) first = m; else sum += edgeTerm(prev, m, n);
            prev = m;
            ++k;
        }
        a = b;
        ha = hb;
    }
    if (k < 3) return 0.0;
    sum += edgeTerm(prev, first, n);
    return clamp(sum / (2.0 * PI), 0.0, 1.0);
}

// The ray eye + t d meets the face at t (1e30: beside it); front: on the face's front.
float rayFace(vec3 d, out bool front) {
    front = false;
    float dn = dot(faceNormal, d);
    if (abs(dn) < 1e-30) return 1e30;
    float t = dot(faceNormal, corner[0] - eye) / dn;
    if (!(t > 0.0)) return 1e30;
    vec3 x = eye + t * d;
    for (int i = 0; i < 4; ++i) {
        if (i >= cornerCount) break;
        vec3 a = corner[i], b = corner[i + 1 < cornerCount ? i + 1 : 0];
        if (dot(cross(b - a, x - a), faceNormal) < 0.0) return 1e30;
    }
    front = dn < 0.0;
    return t;
}

float visibleFraction(vec3 p, vec3 n) {
    if (kind == 0) return cubeVisible(cube, at, p, n, cubeTexel);
    vec3 q = p + n * (1.5 * sunTexel);
    vec4 c = sunViewProj * vec4(q, 1.0);
    vec2 uv = 0.5 * c.xy / c.w + 0.5;
    float d = radius - dot(q - centre, at);
    return d - 2.0 * sunTexel <= texture(sunMap, uv).r ? 1.0 : 0.0;
}

void main() {
    ivec2 xy = ivec2(int(gl_FragCoord.x), height - 1 - int(gl_FragCoord.y));
    vec3 s = texelFetch(scale, xy, 0).rgb;
    vec3 o = texelFetch(offset, xy, 0).rgb;
    vec3 value = vec3(0.0);
    if (any(greaterThan(s, vec3(0.0)))) {
        vec3 p = texelFetch(receiverPoint, xy, 0).rgb;
        vec3 n = texelFetch(receiverNormal, xy, 0).rgb;
        float g = 0.0;
        if (dot(n, n) > 0.0) {
            if (kind == 0) {
                vec3 v = at - p;
                float d2 = dot(v, v);
                float c = dot(n, v) / sqrt(d2);
                if (d2 > 1e-18 && c > 0.0) g = c / d2 * visibleFraction(p, n);
            } else if (kind == 1) {
                float c = dot(n, at);
                if (c > 0.0) g = c * visibleFraction(p, n);
            } else {
                // pi F times the mean visibility of the face's points (its unit radiance).
                float F = faceFormFactor(p, n);
                if (F > 0.0)
                    g = PI * F * 0.25 *
                        (cubeVisible(face0, facePoint[0], p, n, faceTexel) +
                         cubeVisible(face1, facePoint[1], p, n, faceTexel) +
                         cubeVisible(face2, facePoint[2], p, n, faceTexel) +
                         cubeVisible(face3, facePoint[3], p, n, faceTexel));
            }
        }
        vec3 now = texelFetch(rest, xy, 0).rgb + radiance * g;
        float lum = dot(now, vec3(0.2126, 0.7152, 0.0722));
        float light = texelFetch(photoLight, xy, 0).r;
        vec3 R = texelFetch(rho, xy, 0).rgb;
        if (havePooled == 1 && light > 0.0 && lum > poolAbove * light) {
            float w = poolAbove * light / lum;
            int r = min(maxPoolRadius, int(floor(float(poolRadius) * sqrt(1.0 / w) + 0.5)));
            R = w * texelFetch(rhoPool, xy, 0).rgb +
                (1.0 - w) * texelFetch(pooled, ivec3(xy, r - poolRadius), 0).rgb;
        }
        value = max(R * (max(now, 0.0) + delta), 0.0);
    }
    vec3 shown = s * value + o;
    if (kind == 2) {  // the lamp's face, where it is, in front of what the pixel shows
        // relight/dynamic/quick_light.h, faceCoverage: the share of k x k camera samples.
        float shows = length(texelFetch(surface, xy, 0).rgb - eye);
        int k = samplesPerSide;
        float all = 0.0, lit = 0.0;
        for (int i = 0; i < 64; ++i) {
            if (i >= k * k) break;
            vec2 uv = vec2(xy) - 0.5 + (vec2(i % k, i / k) + 0.5) / float(k);
            vec3 d = normalize(worldFromCamera *
                               vec3((uv - intrinsics.zw) / intrinsics.xy, 1.0));
            bool front;
            if (rayFace(d, front) < shows) {
                all += 1.0;
                lit += front ? 1.0 : 0.0;
            }
        }
        float n = float(k * k);
        shown = shown * (1.0 - all / n) + radiance * (lit / n);
    }
    color = vec4(gain * shown, 1.0);
}
)";

/// Per pixel RGB from `values` (stride floats per pixel, from `first`) as an RGB32F texture.
GLuint rgbTexture(int w, int h, const std::vector<float>& values, size_t stride, size_t first) {
    const size_t pixels = static_cast<size_t>(w) * static_cast<size_t>(h);
    std::vector<float> rgb(3 * pixels, 0.0f);
    if (values.size() >= stride * pixels)
        for (size_t px = 0; px < pixels; ++px)
            for (size_t c = 0; c < 3; ++c) rgb[3 * px + c] = values[stride * px + first + c];
    return gl::makeTexture2D(GL_RGB32F, w, h, GL_RGB, GL_FLOAT, rgb.data(), GL_NEAREST);
}

/// A colour target of distances and its depth buffer (a cube face, or the sun's square).
void attachDistanceTarget(GLuint fbo, GLenum face, GLuint tex, GLuint depth) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, face, tex, 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("viewer: the OpenGL driver cannot render a float shadow map");
}

GLuint depthBuffer(int side) {
    GLuint rb = 0;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, side, side);
    return rb;
}

void setNearest(GLenum target) {
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

}  // namespace

size_t GpuMovedLight::bytesNeeded(size_t pixels) {
    // Per pixel: point, normal, surface, rest, rho, rhoPool, scale and offset as RGB32F, photoLight
    // as R32F, and the pooled reflectance's RGB32F layers (setFrame).
    const size_t radii = static_cast<size_t>(kMaxPoolRadius - kPoolRadius + 1);
    const size_t perPixel = 8 * 12 + 4 + radii * 12;
    // A cube of distances and its depth (4 bytes each) per point lamp map and face point,
    // and the sun's square.
    const size_t cube = 6 * 8 * static_cast<size_t>(kCubeSide) * kCubeSide;
    const size_t faces = kFacePoints * 6 * 4 * static_cast<size_t>(kFaceCubeSide) * kFaceCubeSide +
                         8 * static_cast<size_t>(kFaceCubeSide) * kFaceCubeSide;
    const size_t sun = 8 * static_cast<size_t>(kSunSide) * kSunSide;
    return pixels * perPixel + cube + faces + sun;
}

size_t GpuMovedLight::driverFreeMemory() {
    // Both extensions give KiB.
    if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
        GLint kib = 0;
        glGetIntegerv(0x9049, &kib);  // GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
        return kib > 0 ? static_cast<size_t>(kib) * 1024 : 0;
    }
    if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
        GLint info[4] = {0, 0, 0, 0};
        glGetIntegerv(0x87FC, info);  // TEXTURE_FREE_MEMORY_ATI: the free pool first
        return info[0] > 0 ? static_cast<size_t>(info[0]) * 1024 : 0;
    }
    return 0;
}

GpuMovedLight::GpuMovedLight(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("GpuMovedLight: the photo has no pixels");
    program_ = gl::link(gl::kFullScreenVertexShader, kFrameFragment);
    shadowProgram_ = gl::link(kShadowVertex, kShadowFragment);
    glGenVertexArrays(1, &vao_);
    glGenVertexArrays(1, &blockerVao_);
    glGenBuffers(1, &blockerBuf_);
    // The cube of distances: far (1e30) where nothing is drawn.
    glGenTextures(1, &cubeTex_);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cubeTex_);
    for (int f = 0; f < 6; ++f)
        glTexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_R32F, kCubeSide,
                     kCubeSide, 0, GL_RED, GL_FLOAT, nullptr);
    setNearest(GL_TEXTURE_CUBE_MAP);
    cubeDepth_ = depthBuffer(kCubeSide);
    glGenFramebuffers(6, cubeFbo_);
    for (int f = 0; f < 6; ++f)
        attachDistanceTarget(cubeFbo_[f], static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f),
                             cubeTex_, cubeDepth_);
    faceDepth_ = depthBuffer(kFaceCubeSide);
    for (int i = 0; i < kFacePoints; ++i) {
        glGenTextures(1, &faceTex_[i]);
        glBindTexture(GL_TEXTURE_CUBE_MAP, faceTex_[i]);
        for (int f = 0; f < 6; ++f)
            glTexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_R32F,
                         kFaceCubeSide, kFaceCubeSide, 0, GL_RED, GL_FLOAT, nullptr);
        setNearest(GL_TEXTURE_CUBE_MAP);
        glGenFramebuffers(6, faceFbo_[i]);
        for (int f = 0; f < 6; ++f)
            attachDistanceTarget(faceFbo_[i][f],
                                 static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f),
                                 faceTex_[i], faceDepth_);
    }
    sunTex_ = gl::makeTexture2D(GL_R32F, kSunSide, kSunSide, GL_RED, GL_FLOAT, nullptr, GL_NEAREST);
    sunDepth_ = depthBuffer(kSunSide);
    glGenFramebuffers(1, &sunFbo_);
    attachDistanceTarget(sunFbo_, GL_TEXTURE_2D, sunTex_, sunDepth_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(program_);
    const char* units[] = {"receiverPoint", "receiverNormal", "rest",   "rho",
                           "rhoPool",       "photoLight",     "scale",  "offset",
                           "pooled",        "cube",           "sunMap", "face0",
                           "face1",         "face2",          "face3",  "surface"};
    for (int u = 0; u < 16; ++u) glUniform1i(glGetUniformLocation(program_, units[u]), u);
    glUniform1i(glGetUniformLocation(program_, "height"), height_);
    glUseProgram(0);
}

GpuMovedLight::~GpuMovedLight() {
    for (GLuint t : {surfaceTex_, pointTex_, normalTex_, restTex_, rhoTex_, rhoPoolTex_,
                     photoLightTex_, scaleTex_, offsetTex_, pooledTex_, cubeTex_, sunTex_})
        if (t) glDeleteTextures(1, &t);
    glDeleteTextures(kFacePoints, faceTex_);
    for (int i = 0; i < kFacePoints; ++i) glDeleteFramebuffers(6, faceFbo_[i]);
    glDeleteRenderbuffers(1, &faceDepth_);
    glDeleteRenderbuffers(1, &cubeDepth_);
    glDeleteRenderbuffers(1, &sunDepth_);
    glDeleteFramebuffers(6, cubeFbo_);
    glDeleteFramebuffers(1, &sunFbo_);
    glDeleteBuffers(1, &blockerBuf_);
    glDeleteVertexArrays(1, &blockerVao_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
    glDeleteProgram(shadowProgram_);
}

void GpuMovedLight::setFrame(const MovedLightFrame& f) {
    const PixelLightTerms& t = f.terms;
    const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
    if (t.width != width_ || t.height != height_ || f.receivers.size() != 6 * pixels ||
        f.scale.size() != 3 * pixels || f.offset.size() != 3 * pixels)
        throw std::invalid_argument("GpuMovedLight: a frame of another size than the photo");
    for (GLuint* tex : {&pointTex_, &normalTex_, &restTex_, &rhoTex_, &rhoPoolTex_, &photoLightTex_,
                        &scaleTex_, &offsetTex_})
        if (*tex) glDeleteTextures(1, tex);
    pointTex_ = rgbTexture(width_, height_, f.receivers, 6, 0);
    if (surfaceTex_) glDeleteTextures(1, &surfaceTex_);
    surfaceTex_ = rgbTexture(width_, height_, f.surface, 3, 0);  // zeros without a face
    normalTex_ = rgbTexture(width_, height_, f.receivers, 6, 3);
    restTex_ = rgbTexture(width_, height_, t.rest, 3, 0);
    rhoTex_ = rgbTexture(width_, height_, t.rho, 3, 0);
    rhoPoolTex_ = rgbTexture(width_, height_, t.rhoPool, 3, 0);
    scaleTex_ = rgbTexture(width_, height_, f.scale, 3, 0);
    offsetTex_ = rgbTexture(width_, height_, f.offset, 3, 0);
    photoLightTex_ = gl::makeTexture2D(GL_R32F, width_, height_, GL_RED, GL_FLOAT,
                                       t.photoLight.data(), GL_NEAREST);
    const int radii = kMaxPoolRadius - kPoolRadius + 1;
    pooled_ = t.pooled && t.pooled->size() == 3 * pixels * static_cast<size_t>(radii);
    // The pooled reflectance does not change with the edit: uploaded again only when the
    // frame's table is another one (74 MB at 1280 x 960).
    if (!pooledTex_ || t.pooled != pooledData_) {
        if (pooledTex_) glDeleteTextures(1, &pooledTex_);
        const std::vector<float> none(pooled_ ? 0 : 3 * pixels, 0.0f);
        glGenTextures(1, &pooledTex_);
        glBindTexture(GL_TEXTURE_2D_ARRAY, pooledTex_);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGB32F, width_, height_, pooled_ ? radii : 1, 0,
                     GL_RGB, GL_FLOAT, pooled_ ? t.pooled->data() : none.data());
        setNearest(GL_TEXTURE_2D_ARRAY);
        pooledData_ = t.pooled;
    }
    for (int c = 0; c < 3; ++c) {
        eye_[c] = static_cast<float>(f.camera.position()[c]);
        radiance_[c] = static_cast<float>(t.radiance[c]);
        delta_[c] = static_cast<float>(t.delta[c]);
    }
    // The camera, column-major as GLSL reads a mat3 (glm's layout).
    const glm::dmat3 worldFromCamera = glm::transpose(f.camera.cameraFromWorldR);
    for (int col = 0; col < 3; ++col)
        for (int row = 0; row < 3; ++row)
            worldFromCamera_[3 * col + row] = static_cast<float>(worldFromCamera[col][row]);
    const double intrinsics[4] = {f.camera.fx, f.camera.fy, f.camera.cx, f.camera.cy};
    for (int i = 0; i < 4; ++i) intrinsics_[i] = static_cast<float>(intrinsics[i]);
    samplesPerSide_ = std::clamp(f.samplesPerSide, 1, 8);
    // The blockers, and their bounding sphere (the sun's map covers it).
    glBindVertexArray(blockerVao_);
    glBindBuffer(GL_ARRAY_BUFFER, blockerBuf_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(f.blockers.size() * sizeof(float)),
                 f.blockers.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);
    blockerVertices_ = static_cast<GLsizei>(f.blockers.size() / 3);
    radiosity::Bounds3 b;
    for (size_t i = 0; i + 2 < f.blockers.size(); i += 3)
        b.extend(radiosity::Vec3(f.blockers[i], f.blockers[i + 1], f.blockers[i + 2]));
    centre_ = blockerVertices_ > 0 ? 0.5 * (b.lo + b.hi) : radiosity::Vec3{0, 0, 0};
    radius_ = blockerVertices_ > 0 ? std::max(0.5 * glm::length(b.hi - b.lo), 1e-3) : 1.0;
    hasFrame_ = true;
}

void GpuMovedLight::shadowPass(GLuint fbo, const float* viewProj, int side) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, side, side);
    glClearColor(1e30f, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUniformMatrix4fv(glGetUniformLocation(shadowProgram_, "viewProj"), 1, GL_FALSE, viewProj);
    glDrawArrays(GL_TRIANGLES, 0, blockerVertices_);
}

void GpuMovedLight::renderCube(const glm::vec3& at, const GLuint* fbos, int side) {
    // The cube map's faces as OpenGL orients them (the lookup direction's major axis).
    const std::array<glm::vec3, 6> dir = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0),
                                          glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
                                          glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
    const std::array<glm::vec3, 6> up = {glm::vec3(0, -1, 0), glm::vec3(0, -1, 0),
                                         glm::vec3(0, 0, 1),  glm::vec3(0, 0, -1),
                                         glm::vec3(0, -1, 0), glm::vec3(0, -1, 0)};
    glUniform1i(glGetUniformLocation(shadowProgram_, "kind"), 0);
    glUniform3fv(glGetUniformLocation(shadowProgram_, "at"), 1, glm::value_ptr(at));
    const float reach = glm::length(at - glm::vec3(centre_)) + static_cast<float>(radius_);
    const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, 1e-4f * reach, 2.0f * reach);
    for (int f = 0; f < 6; ++f) {
        const glm::mat4 vp =
            proj * glm::lookAt(at, at + dir[static_cast<size_t>(f)], up[static_cast<size_t>(f)]);
        shadowPass(fbos[f], glm::value_ptr(vp), side);
    }
}

void GpuMovedLight::renderShadowMap(const radiosity::ShadowSource& source) {
    GLint viewport[4];
    GLint target = 0;
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &target);
    const bool point = source.kind == radiosity::ShadowSource::Kind::point;
    const glm::vec3 at(source.at), centre(centre_);
    const float R = static_cast<float>(radius_);
    glUseProgram(shadowProgram_);
    glUniform1i(glGetUniformLocation(shadowProgram_, "kind"), point ? 0 : 1);
    glUniform3fv(glGetUniformLocation(shadowProgram_, "at"), 1, glm::value_ptr(at));
    glUniform3fv(glGetUniformLocation(shadowProgram_, "centre"), 1, glm::value_ptr(centre));
    glUniform1f(glGetUniformLocation(shadowProgram_, "radius"), R);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);  // one-sided faces block from either side, as Embree's rays
    glBindVertexArray(blockerVao_);
    if (point) {
        renderCube(at, cubeFbo_, kCubeSide);
    } else if (source.kind == radiosity::ShadowSource::Kind::face) {
        const auto points = source.facePoints();
        for (int i = 0; i < kFacePoints; ++i)
            renderCube(glm::vec3(points[static_cast<size_t>(i)]), faceFbo_[i], kFaceCubeSide);
    } else {
        const glm::vec3 side = std::abs(at.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
        const glm::mat4 vp =
            glm::ortho(-R, R, -R, R, 0.0f, 2.0f * R) * glm::lookAt(centre + R * at, centre, side);
        std::copy_n(glm::value_ptr(vp), 16, sunViewProj_);
        shadowPass(sunFbo_, sunViewProj_, kSunSide);
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
}

void GpuMovedLight::setFaceUniforms(const radiosity::ShadowSource& source) {
    if (source.kind != radiosity::ShadowSource::Kind::face) return;
    const size_t count = source.corners.size();
    if (count != 3 && count != 4)
        throw std::invalid_argument("GpuMovedLight: a face of 3 or 4 corners");
    float corners[12] = {}, points[12] = {};
    const auto p = source.facePoints();
    for (size_t i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) {
            corners[3 * i + static_cast<size_t>(c)] =
                static_cast<float>(source.corners[std::min(i, count - 1)][c]);
            points[3 * i + static_cast<size_t>(c)] = static_cast<float>(p[i][c]);
        }
    const radiosity::Vec3 a =
        glm::cross(source.corners[1] - source.corners[0], source.corners[2] - source.corners[0]);
    const double length = glm::length(a);
    if (!(length > 0)) throw std::invalid_argument("GpuMovedLight: a face of no area");
    const glm::vec3 normal(a / length);
    const auto uniform = [&](const char* name) { return glGetUniformLocation(program_, name); };
    glUniform3fv(uniform("corner"), 4, corners);
    glUniform3fv(uniform("facePoint"), 4, points);
    glUniform1i(uniform("cornerCount"), static_cast<int>(count));
    glUniform3fv(uniform("faceNormal"), 1, glm::value_ptr(normal));
    glUniform1f(uniform("faceTexel"), 1.5707963f / kFaceCubeSide);
    glUniform3fv(uniform("eye"), 1, eye_);
    glUniformMatrix3fv(uniform("worldFromCamera"), 1, GL_FALSE, worldFromCamera_);
    glUniform4fv(uniform("intrinsics"), 1, intrinsics_);
    glUniform1i(uniform("samplesPerSide"), samplesPerSide_);
}

void GpuMovedLight::draw(const radiosity::ShadowSource& source, float gain) {
    if (!hasFrame_) throw std::logic_error("GpuMovedLight::draw before setFrame");
    renderShadowMap(source);
    glUseProgram(program_);
    const GLuint textures[] = {pointTex_,   normalTex_,     restTex_,  rhoTex_,
                               rhoPoolTex_, photoLightTex_, scaleTex_, offsetTex_};
    for (int u = 0; u < 8; ++u) gl::bindUnit(u, GL_TEXTURE_2D, textures[u]);
    gl::bindUnit(8, GL_TEXTURE_2D_ARRAY, pooledTex_);
    gl::bindUnit(9, GL_TEXTURE_CUBE_MAP, cubeTex_);
    gl::bindUnit(10, GL_TEXTURE_2D, sunTex_);
    for (int i = 0; i < kFacePoints; ++i) gl::bindUnit(11 + i, GL_TEXTURE_CUBE_MAP, faceTex_[i]);
    gl::bindUnit(15, GL_TEXTURE_2D, surfaceTex_);
    const auto uniform = [&](const char* name) { return glGetUniformLocation(program_, name); };
    const glm::vec3 at(source.at), centre(centre_);
    glUniform1i(uniform("kind"), static_cast<int>(source.kind));
    glUniform3fv(uniform("at"), 1, glm::value_ptr(at));
    setFaceUniforms(source);
    glUniform3fv(uniform("centre"), 1, glm::value_ptr(centre));
    glUniform1f(uniform("radius"), static_cast<float>(radius_));
    glUniformMatrix4fv(uniform("sunViewProj"), 1, GL_FALSE, sunViewProj_);
    // A cube face spans 90 degrees: pi / 2 over its side, radians per texel.
    glUniform1f(uniform("cubeTexel"), 1.5707963f / kCubeSide);
    glUniform1f(uniform("sunTexel"), static_cast<float>(2 * radius_ / kSunSide));
    glUniform3fv(uniform("radiance"), 1, radiance_);
    glUniform3fv(uniform("delta"), 1, delta_);
    glUniform1i(uniform("havePooled"), pooled_ ? 1 : 0);
    glUniform1f(uniform("poolAbove"), static_cast<float>(kPoolAbove));
    glUniform1i(uniform("poolRadius"), kPoolRadius);
    glUniform1i(uniform("maxPoolRadius"), kMaxPoolRadius);
    glUniform1f(uniform("gain"), gain);
    glDisable(GL_BLEND);
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace relight::viewer
