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
uniform int height;
uniform int kind;                   // 0 point lamp, 1 sun
uniform vec3 at;
uniform vec3 centre;
uniform float radius;
uniform mat4 sunViewProj;
uniform float cubeTexel;            // radians per cube texel
uniform float sunTexel;             // metres per sun texel
uniform vec3 radiance;              // L_m
uniform vec3 delta;
uniform int havePooled;
uniform float poolAbove;
uniform int poolRadius;
uniform int maxPoolRadius;
uniform float gain;
out vec4 color;

float visibleFraction(vec3 p, vec3 n) {
    if (kind == 0) {
        float d = length(p - at);
        float texel = cubeTexel * d;
        vec3 q = p + n * (1.5 * texel);
        return length(q - at) - 2.0 * texel <= texture(cube, q - at).r ? 1.0 : 0.0;
    }
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
            } else {
                float c = dot(n, at);
                if (c > 0.0) g = c * visibleFraction(p, n);
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
    color = vec4(gain * (s * value + o), 1.0);
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
    sunTex_ = gl::makeTexture2D(GL_R32F, kSunSide, kSunSide, GL_RED, GL_FLOAT, nullptr, GL_NEAREST);
    sunDepth_ = depthBuffer(kSunSide);
    glGenFramebuffers(1, &sunFbo_);
    attachDistanceTarget(sunFbo_, GL_TEXTURE_2D, sunTex_, sunDepth_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(program_);
    const char* units[] = {"receiverPoint", "receiverNormal", "rest",  "rho",
                           "rhoPool",       "photoLight",     "scale", "offset",
                           "pooled",        "cube",           "sunMap"};
    for (int u = 0; u < 11; ++u) glUniform1i(glGetUniformLocation(program_, units[u]), u);
    glUniform1i(glGetUniformLocation(program_, "height"), height_);
    glUseProgram(0);
}

GpuMovedLight::~GpuMovedLight() {
    for (GLuint t : {pointTex_, normalTex_, restTex_, rhoTex_, rhoPoolTex_, photoLightTex_,
                     scaleTex_, offsetTex_, pooledTex_, cubeTex_, sunTex_})
        if (t) glDeleteTextures(1, &t);
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
        radiance_[c] = static_cast<float>(t.radiance[c]);
        delta_[c] = static_cast<float>(t.delta[c]);
    }
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
        // The cube map's faces as OpenGL orients them (the lookup direction's major axis).
        const std::array<glm::vec3, 6> dir = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0),
                                              glm::vec3(0, 1, 0), glm::vec3(0, -1, 0),
                                              glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
        const std::array<glm::vec3, 6> up = {glm::vec3(0, -1, 0), glm::vec3(0, -1, 0),
                                             glm::vec3(0, 0, 1),  glm::vec3(0, 0, -1),
                                             glm::vec3(0, -1, 0), glm::vec3(0, -1, 0)};
        const float reach = glm::length(at - centre) + R;
        const glm::mat4 proj =
            glm::perspective(glm::radians(90.0f), 1.0f, 1e-4f * reach, 2.0f * reach);
        for (int f = 0; f < 6; ++f) {
            const glm::mat4 vp = proj * glm::lookAt(at, at + dir[static_cast<size_t>(f)],
                                                    up[static_cast<size_t>(f)]);
            shadowPass(cubeFbo_[f], glm::value_ptr(vp), kCubeSide);
        }
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

void GpuMovedLight::draw(const radiosity::ShadowSource& source, float gain) {
    if (!hasFrame_) throw std::logic_error("GpuMovedLight::draw before setFrame");
    const bool point = source.kind == radiosity::ShadowSource::Kind::point;
    renderShadowMap(source);
    glUseProgram(program_);
    const GLuint textures[] = {pointTex_,   normalTex_,     restTex_,  rhoTex_,
                               rhoPoolTex_, photoLightTex_, scaleTex_, offsetTex_};
    for (int u = 0; u < 8; ++u) gl::bindUnit(u, GL_TEXTURE_2D, textures[u]);
    gl::bindUnit(8, GL_TEXTURE_2D_ARRAY, pooledTex_);
    gl::bindUnit(9, GL_TEXTURE_CUBE_MAP, cubeTex_);
    gl::bindUnit(10, GL_TEXTURE_2D, sunTex_);
    const auto uniform = [&](const char* name) { return glGetUniformLocation(program_, name); };
    const glm::vec3 at(source.at), centre(centre_);
    glUniform1i(uniform("kind"), point ? 0 : 1);
    glUniform3fv(uniform("at"), 1, glm::value_ptr(at));
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
