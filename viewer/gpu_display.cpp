#include "viewer/gpu_display.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "relight/display/multipass.h"
#include "viewer/gl_util.h"

namespace relight::viewer {

namespace {

using gl::bindUnit;
using gl::makeTexture2D;

// The per-pixel work of renderRatio() (relight/display/ratio_display.cpp) and applyOverlay()
// (relight/dynamic/dynamic_relighting.h); see gpu_display.h. Image row y is fragment row
// height - 1 - y, so that the target shows the photo upright.
const char* kDisplayShader = R"(#version 330 core
uniform isamplerBuffer pixelStart;    // per pixel + 1: (entry start, emitter start)
uniform isamplerBuffer entryVertex;
uniform samplerBuffer entryWeight;
uniform isamplerBuffer emitterLight;
uniform samplerBuffer emitterFraction;
uniform samplerBuffer vertexValue;    // per leaf vertex: ratio k H/D, or H
uniform samplerBuffer lightRadiance;  // per real light, now
uniform sampler2D photoA;             // A = T_rest / rest; alpha: unshaded fraction U
uniform sampler2D photo8;             // clamp(T_rest, 0, 1), 8 bits sRGB: the paper's texture
uniform sampler2D overlay;            // virtual parts: added radiance; alpha: real share
uniform sampler2D factor;             // B view: rho / (pi sum w)
uniform sampler2D image;              // fixed image
uniform int width;
uniform int height;
uniform int view;       // 0 relit, 1 B, 2 image
uniform int multipass;  // 0: float target; 1: pass `pass` of the 8-bit target
uniform int pass;
uniform float gain;
out vec4 color;

void main() {
    ivec2 xy = ivec2(int(gl_FragCoord.x), height - 1 - int(gl_FragCoord.y));
    if (view == 2) {
        color = vec4(gain * texelFetch(image, xy, 0).rgb, 1.0);
        return;
    }
    int px = xy.y * width + xy.x;
    ivec2 s0 = texelFetch(pixelStart, px).xy;
    ivec2 s1 = texelFetch(pixelStart, px + 1).xy;
    if (view == 1) {
        vec3 sum = vec3(0.0);
        for (int k = s0.x; k < s1.x; ++k)
            sum += texelFetch(entryWeight, k).r *
                   texelFetch(vertexValue, texelFetch(entryVertex, k).r).rgb;
        color = vec4(gain * texelFetch(factor, xy, 0).rgb * sum, 1.0);
        return;
    }
    vec4 a = texelFetch(photoA, xy, 0);
    vec4 o = texelFetch(overlay, xy, 0);
    vec3 emit = vec3(0.0);
    float rest = 1.0;  // the pixel's share that is not an emitting face
    for (int k = s0.y; k < s1.y; ++k) {
        float f = texelFetch(emitterFraction, k).r;
        emit += f * texelFetch(lightRadiance, texelFetch(emitterLight, k).r).rgb;
        rest -= f;
    }
    if (multipass == 0) {
        vec3 sum = vec3(a.a);
        for (int k = s0.x; k < s1.x; ++k)
            sum += texelFetch(entryWeight, k).r *
                   texelFetch(vertexValue, texelFetch(entryVertex, k).r).rgb;
        vec3 value = max(emit + a.rgb * sum, 0.0);
        color = vec4(gain * (o.a * value + o.rgb), 1.0);
        return;
    }
    // Loscos et al. 2000, §5.3: pass k modulates the texture by the vertex colour
    // clamp(r - k, 0, 1), clamped per vertex as glColor is, then interpolated. The texture
    // is T_rest itself (A = T_rest / rest can exceed the 8-bit range at a lamp's edge) and the
    // weights are divided by rest instead: they sum to 1, so no pass exceeds the texture.
    float k0 = float(pass);
    vec3 sum = vec3(a.a * clamp(gain - k0, 0.0, 1.0));
    for (int k = s0.x; k < s1.x; ++k)
        sum += texelFetch(entryWeight, k).r *
               clamp(gain * texelFetch(vertexValue, texelFetch(entryVertex, k).r).rgb - k0,
                     0.0, 1.0);
    vec3 value = rest > 1e-6 ? o.a * texelFetch(photo8, xy, 0).rgb * sum / rest : vec3(0.0);
    if (pass == 0) value += gain * (o.a * emit + o.rgb);
    color = vec4(value, 1.0);
}
)";

// Linear values to the window: clipped to [0, 1], sRGB transfer function (IEC 61966-2-1),
// as relight/io/image.cpp writes a PNG.
const char* kPresentShader = R"(#version 330 core
uniform sampler2D result;
in vec2 uv;
out vec4 color;
void main() {
    vec3 c = clamp(texture(result, uv).rgb, 0.0, 1.0);
    vec3 encoded = mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055,
                       step(vec3(0.0031308), c));
    color = vec4(encoded, 1.0);
}
)";

GLuint link(const char* fragment) {
    return gl::link(gl::kFullScreenVertexShader, fragment);
}

/// A texture buffer over `bytes` of data (at least one element, so that an empty list
/// still binds).
void makeTextureBuffer(GLuint& buf, GLuint& tex, GLenum format, const void* data, size_t bytes,
                       size_t elementBytes, GLenum usage = GL_STATIC_DRAW) {
    glGenBuffers(1, &buf);
    glBindBuffer(GL_TEXTURE_BUFFER, buf);
    std::vector<unsigned char> zero;
    if (bytes == 0) {
        zero.assign(elementBytes, 0);
        data = zero.data();
        bytes = elementBytes;
    }
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(bytes), data, usage);
    glGenTextures(1, &tex);
    glBindTexture(GL_TEXTURE_BUFFER, tex);
    glTexBuffer(GL_TEXTURE_BUFFER, format, buf);
}

void makeTarget(GLuint& fbo, GLuint& tex, GLenum internalFormat, int w, int h) {
    tex = makeTexture2D(internalFormat, w, h, GL_RGBA, GL_FLOAT, nullptr);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex, 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error(
            "viewer: the OpenGL driver cannot render into a " +
            std::string(internalFormat == GL_RGBA32F ? "float" : "8-bit sRGB") + " target");
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<float> rgba(const Image& img, float alpha) {
    std::vector<float> out(static_cast<size_t>(img.width) * img.height * 4);
    for (size_t i = 0; i < static_cast<size_t>(img.width) * img.height; ++i) {
        for (int c = 0; c < 3; ++c) out[i * 4 + c] = img.rgb[i * 3 + c];
        out[i * 4 + 3] = alpha;
    }
    return out;
}

}  // namespace

GpuRatioDisplay::GpuRatioDisplay(const PreparedImage& p)
    : width_(p.display.width),
      height_(p.display.height),
      lights_(static_cast<int>(p.photoRadiance.size())) {
    const DisplayMap& m = p.display;
    if (width_ <= 0 || height_ <= 0 || p.photo.width != width_ || p.photo.height != height_)
        throw std::invalid_argument("GpuRatioDisplay: the display map and the photo differ");
    const size_t pixels = static_cast<size_t>(width_) * height_;

    program_ = link(kDisplayShader);
    presentProgram_ = link(kPresentShader);
    glGenVertexArrays(1, &vao_);

    shown_.assign(p.vertexCount(), 0);
    for (int v : m.vertex) shown_[static_cast<size_t>(v)] = 1;
    std::vector<int> starts(2 * (pixels + 1));
    for (size_t i = 0; i <= pixels; ++i) {
        starts[2 * i] = m.start[i];
        starts[2 * i + 1] = m.emitterStart[i];
    }
    makeTextureBuffer(pixelStartBuf_, pixelStartTex_, GL_RG32I, starts.data(),
                      starts.size() * sizeof(int), 2 * sizeof(int));
    makeTextureBuffer(vertexBuf_, vertexTex_, GL_R32I, m.vertex.data(),
                      m.vertex.size() * sizeof(int), sizeof(int));
    makeTextureBuffer(weightBuf_, weightTex_, GL_R32F, m.weight.data(),
                      m.weight.size() * sizeof(float), sizeof(float));
    makeTextureBuffer(emitterLightBuf_, emitterLightTex_, GL_R32I, m.emitterLight.data(),
                      m.emitterLight.size() * sizeof(int), sizeof(int));
    makeTextureBuffer(emitterFracBuf_, emitterFracTex_, GL_R32F, m.emitterFraction.data(),
                      m.emitterFraction.size() * sizeof(float), sizeof(float));
    const std::vector<float> zeroVertices(p.vertexCount() * 4, 0.0f);
    makeTextureBuffer(valueBuf_, valueTex_, GL_RGBA32F, zeroVertices.data(),
                      zeroVertices.size() * sizeof(float), 4 * sizeof(float), GL_DYNAMIC_DRAW);
    const std::vector<float> zeroLights(static_cast<size_t>(lights_) * 4, 0.0f);
    makeTextureBuffer(radianceBuf_, radianceTex_, GL_RGBA32F, zeroLights.data(),
                      zeroLights.size() * sizeof(float), 4 * sizeof(float), GL_DYNAMIC_DRAW);

    // A = T_rest / rest, as renderRatio() divides it (0 where the pixel is all emitter).
    std::vector<float> a(pixels * 4), a8(pixels * 4);
    std::vector<unsigned char> bytes(pixels * 4);
    for (size_t i = 0; i < pixels; ++i) {
        Rgb T{p.photo.rgb[3 * i], p.photo.rgb[3 * i + 1], p.photo.rgb[3 * i + 2]};
        double emitterFraction = 0;
        for (int k = m.emitterStart[i]; k < m.emitterStart[i + 1]; ++k) {
            T -= p.photoRadiance[static_cast<size_t>(m.emitterLight[k])] *
                 static_cast<double>(m.emitterFraction[k]);
            emitterFraction += static_cast<double>(m.emitterFraction[k]);
        }
        const double rest = 1.0 - emitterFraction;
        for (int c = 0; c < 3; ++c) {
            const double A = rest > 1e-6 ? T[c] / rest : 0.0;
            a[i * 4 + c] = static_cast<float>(A);
            bytes[i * 4 + c] = static_cast<unsigned char>(
                std::lround(255.0 * srgbEncode(std::clamp(T[c], 0.0, 1.0))));
        }
        a[i * 4 + 3] = m.unshaded[i];
        bytes[i * 4 + 3] = 255;
        anyUnshaded_ = anyUnshaded_ || m.unshaded[i] > 0;
    }
    photoTex_ = makeTexture2D(GL_RGBA32F, width_, height_, GL_RGBA, GL_FLOAT, a.data());
    photo8Tex_ =
        makeTexture2D(GL_SRGB8_ALPHA8, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    std::vector<float> clear(pixels * 4, 0.0f);
    for (size_t i = 0; i < pixels; ++i) clear[i * 4 + 3] = 1.0f;  // real share 1: nothing added
    overlayTex_ = makeTexture2D(GL_RGBA32F, width_, height_, GL_RGBA, GL_FLOAT, clear.data());
    factorTex_ = makeTexture2D(GL_RGBA32F, width_, height_, GL_RGBA, GL_FLOAT, clear.data());
    imageTex_ = makeTexture2D(GL_RGBA32F, width_, height_, GL_RGBA, GL_FLOAT, clear.data());
    for (GLuint t : {photoTex_, photo8Tex_, overlayTex_, factorTex_, imageTex_}) {
        glBindTexture(GL_TEXTURE_2D, t);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    makeTarget(floatFbo_, floatTex_, GL_RGBA32F, width_, height_);
    makeTarget(byteFbo_, byteTex_, GL_SRGB8_ALPHA8, width_, height_);
    makeTarget(readFbo_, readTex_, GL_RGBA32F, width_, height_);
    lastTex_ = floatTex_;

    glUseProgram(program_);
    const auto unit = [&](const char* name, int u) {
        glUniform1i(glGetUniformLocation(program_, name), u);
    };
    unit("pixelStart", 0);
    unit("entryVertex", 1);
    unit("entryWeight", 2);
    unit("emitterLight", 3);
    unit("emitterFraction", 4);
    unit("vertexValue", 5);
    unit("lightRadiance", 6);
    unit("photoA", 7);
    unit("photo8", 8);
    unit("overlay", 9);
    unit("factor", 10);
    unit("image", 11);
    glUniform1i(glGetUniformLocation(program_, "width"), width_);
    glUniform1i(glGetUniformLocation(program_, "height"), height_);
    glUseProgram(presentProgram_);
    glUniform1i(glGetUniformLocation(presentProgram_, "result"), 0);
    glUseProgram(0);
    setRadiance(p.photoRadiance);
}

GpuRatioDisplay::~GpuRatioDisplay() {
    for (GLuint b : {pixelStartBuf_, vertexBuf_, weightBuf_, emitterLightBuf_, emitterFracBuf_,
                     valueBuf_, radianceBuf_})
        glDeleteBuffers(1, &b);
    for (GLuint t : {pixelStartTex_, vertexTex_, weightTex_, emitterLightTex_, emitterFracTex_,
                     valueTex_, radianceTex_, photoTex_, photo8Tex_, overlayTex_, factorTex_,
                     imageTex_, floatTex_, byteTex_, readTex_})
        glDeleteTextures(1, &t);
    for (GLuint f : {floatFbo_, byteFbo_, readFbo_}) glDeleteFramebuffers(1, &f);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
    glDeleteProgram(presentProgram_);
}

void GpuRatioDisplay::setVertexValues(std::span<const Rgb> values) {
    std::vector<float> v(values.size() * 4);
    maxValue_ = 0;
    for (size_t i = 0; i < values.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            v[i * 4 + c] = static_cast<float>(values[i][c]);
            if (i < shown_.size() && shown_[i] && v[i * 4 + c] > maxValue_)
                maxValue_ = v[i * 4 + c];  // NaN: skipped
        }
    glBindBuffer(GL_TEXTURE_BUFFER, valueBuf_);
    glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(),
                 GL_DYNAMIC_DRAW);
}

void GpuRatioDisplay::setRadiance(std::span<const Rgb> radianceNow) {
    if (static_cast<int>(radianceNow.size()) != lights_)
        throw std::invalid_argument("GpuRatioDisplay: one radiance per real light expected");
    std::vector<float> v(radianceNow.size() * 4, 0.0f);
    for (size_t i = 0; i < radianceNow.size(); ++i)
        for (int c = 0; c < 3; ++c) v[i * 4 + c] = static_cast<float>(radianceNow[i][c]);
    if (v.empty()) return;
    glBindBuffer(GL_TEXTURE_BUFFER, radianceBuf_);
    glBufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(v.size() * sizeof(float)),
                    v.data());
}

void GpuRatioDisplay::setOverlay(const VirtualOverlay& o) {
    glBindTexture(GL_TEXTURE_2D, overlayTex_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Clear the previous box, then write the new one (both small: the parts' projections).
    if (!lastOverlay_.empty()) {
        std::vector<float> clear(static_cast<size_t>(lastOverlay_.width) * lastOverlay_.height * 4,
                                 0.0f);
        for (size_t i = 3; i < clear.size(); i += 4) clear[i] = 1.0f;
        glTexSubImage2D(GL_TEXTURE_2D, 0, lastOverlay_.x0, lastOverlay_.y0, lastOverlay_.width,
                        lastOverlay_.height, GL_RGBA, GL_FLOAT, clear.data());
    }
    if (!o.empty())
        glTexSubImage2D(GL_TEXTURE_2D, 0, o.x0, o.y0, o.width, o.height, GL_RGBA, GL_FLOAT,
                        o.rgba.data());
    lastOverlay_ = VirtualOverlay{o.x0, o.y0, o.width, o.height, {}};
}

void GpuRatioDisplay::uploadImageTexture(GLuint tex, const Image& img, float alpha) {
    if (img.width != width_ || img.height != height_)
        throw std::invalid_argument("GpuRatioDisplay: an image of another size than the photo");
    const std::vector<float> v = rgba(img, alpha);
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, v.data());
}

void GpuRatioDisplay::setBFactor(const Image& factor) {
    uploadImageTexture(factorTex_, factor, 1);
}

void GpuRatioDisplay::setImage(const Image& image) {
    uploadImageTexture(imageTex_, image, 1);
}

int GpuRatioDisplay::passesNeeded(float gain) const {
    // Loscos et al. 2000, §5.3: n = ceil(max B/D); unshaded pixels have ratio 1.
    return multipassCount(gain * std::max(maxValue_, anyUnshaded_ ? 1.0f : 0.0f));
}

int GpuRatioDisplay::draw(View view, Framebuffer fb, float gain) {
    const bool multi = view == View::relit && fb == Framebuffer::multipass8;
    const int passes = multi ? passesNeeded(gain) : 1;
    glBindFramebuffer(GL_FRAMEBUFFER, multi ? byteFbo_ : floatFbo_);
    glViewport(0, 0, width_, height_);
    glDisable(GL_DEPTH_TEST);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(program_);
    bindUnit(0, GL_TEXTURE_BUFFER, pixelStartTex_);
    bindUnit(1, GL_TEXTURE_BUFFER, vertexTex_);
    bindUnit(2, GL_TEXTURE_BUFFER, weightTex_);
    bindUnit(3, GL_TEXTURE_BUFFER, emitterLightTex_);
    bindUnit(4, GL_TEXTURE_BUFFER, emitterFracTex_);
    bindUnit(5, GL_TEXTURE_BUFFER, valueTex_);
    bindUnit(6, GL_TEXTURE_BUFFER, radianceTex_);
    bindUnit(7, GL_TEXTURE_2D, photoTex_);
    bindUnit(8, GL_TEXTURE_2D, photo8Tex_);
    bindUnit(9, GL_TEXTURE_2D, overlayTex_);
    bindUnit(10, GL_TEXTURE_2D, factorTex_);
    bindUnit(11, GL_TEXTURE_2D, imageTex_);
    glUniform1i(glGetUniformLocation(program_, "view"),
                view == View::relit ? 0 : (view == View::B ? 1 : 2));
    glUniform1i(glGetUniformLocation(program_, "multipass"), multi ? 1 : 0);
    glUniform1f(glGetUniformLocation(program_, "gain"), gain);
    glBindVertexArray(vao_);
    if (multi) {
        // Additive blending on linear values, stored sRGB-encoded in 8 bits.
        glEnable(GL_FRAMEBUFFER_SRGB);
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
    }
    for (int k = 0; k < passes; ++k) {
        glUniform1i(glGetUniformLocation(program_, "pass"), k);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBindVertexArray(0);
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    lastTex_ = multi ? byteTex_ : floatTex_;
    return passes;
}

void GpuRatioDisplay::bindFloatTarget() {
    glBindFramebuffer(GL_FRAMEBUFFER, floatFbo_);
    glViewport(0, 0, width_, height_);
    lastTex_ = floatTex_;
}

Image GpuRatioDisplay::read() {
    GLuint fbo = floatFbo_;
    if (lastTex_ == byteTex_) {
        // Decode the 8-bit target to linear floats by sampling it (the sampler undoes the
        // sRGB encoding), rather than trusting glReadPixels' conversion rules.
        glBindFramebuffer(GL_FRAMEBUFFER, readFbo_);
        glViewport(0, 0, width_, height_);
        glUseProgram(program_);
        glUniform1i(glGetUniformLocation(program_, "view"), 2);
        glUniform1f(glGetUniformLocation(program_, "gain"), 1.0f);
        bindUnit(11, GL_TEXTURE_2D, byteTex_);
        glBindVertexArray(vao_);
        // The image view reads texel row height - 1 - j into row j: the copy is flipped.
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glUseProgram(0);
        fbo = readFbo_;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    std::vector<float> v(static_cast<size_t>(width_) * height_ * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, v.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    Image out(width_, height_);
    const bool flipped = fbo == readFbo_;
    for (int j = 0; j < height_; ++j) {
        // Target row j (from the bottom) is image row height - 1 - j; the copy through the
        // image view has flipped it once more.
        const int y = flipped ? j : height_ - 1 - j;
        for (int x = 0; x < width_; ++x)
            for (int c = 0; c < 3; ++c)
                out.at(x, y)[c] = v[(static_cast<size_t>(j) * width_ + x) * 4 + c];
    }
    return out;
}

void GpuRatioDisplay::present(int x, int y, int w, int h) {
    glViewport(x, y, w, h);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_BLEND);
    glUseProgram(presentProgram_);
    bindUnit(0, GL_TEXTURE_2D, lastTex_);
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace relight::viewer
