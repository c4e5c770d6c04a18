// Multi-pass display, CPU reference (Loscos et al. 2000, §5.3, Fig. 19). See multipass.h.
#include "relight/display/multipass.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace relight {

int multipassCount(float maxRatio) {
    if (std::isnan(maxRatio) || maxRatio <= 1.0f) return 1;             // NaN, negative, [0, 1]
    if (maxRatio >= static_cast<float>(kMaxPasses)) return kMaxPasses;  // +Inf included
    return static_cast<int>(std::ceil(maxRatio));
}

float passModulation(float ratio, int pass) {
    if (std::isnan(ratio)) return 0.0f;
    // ratio - pass is exact in float whenever it is in (0, 1] (Sterbenz), so the passes sum
    // to the ratio exactly.
    return std::clamp(ratio - static_cast<float>(pass), 0.0f, 1.0f);
}

std::uint8_t quantize8(float v) {
    if (!(v > 0.0f)) return 0;  // NaN, negative, zero
    if (v >= 1.0f) return 255;
    // A float times 255 is exact in double, and 255 v is never exactly k + 1/2 for a binary
    // fraction v, so this is the correctly rounded unorm8 value.
    return static_cast<std::uint8_t>(std::lround(static_cast<double>(v) * 255.0));
}

std::uint8_t modulate8(std::uint8_t texel, std::uint8_t colour) {
    // round(a b / 255) in integers: a b / 255 is never exactly k + 1/2 (255 is odd), so
    // floor((a b + 127) / 255) is the correctly rounded value.
    const unsigned product = static_cast<unsigned>(texel) * static_cast<unsigned>(colour);
    return static_cast<std::uint8_t>((product + 127u) / 255u);
}

std::uint8_t framebuffer8(float texture, float ratio, int passes) {
    passes = std::clamp(passes, 1, kMaxPasses);
    const std::uint8_t t8 = quantize8(texture);
    unsigned fb = 0;
    for (int k = 0; k < passes; ++k) {
        const float m = passModulation(ratio, k);
        if (m <= 0.0f) break;  // this pass and all later ones add nothing
        fb = std::min(255u, fb + modulate8(t8, quantize8(m)));  // GL_ONE, GL_ONE
        if (fb == 255u) break;                                  // saturated
    }
    return static_cast<std::uint8_t>(fb);
}

std::uint8_t multipassPixel8(float texture, float ratio) {
    return framebuffer8(texture, ratio, multipassCount(ratio));
}

float singlePassPixel(float texture, float ratio) {
    const float t = std::isnan(texture) ? 0.0f : std::clamp(texture, 0.0f, 1.0f);
    const float r = std::isnan(ratio) ? 0.0f : std::max(ratio, 0.0f);
    if (t == 0.0f) return 0.0f;  // 0 * Inf
    return std::min(t * r, 1.0f);
}

namespace {

// The ratio of pixel i (0-based, row-major), channel c, from an RGB image or a grey vector.
struct RgbRatio {
    const Image& image;
    float operator()(size_t i, int c) const { return image.rgb[i * 3 + static_cast<size_t>(c)]; }
    const std::vector<float>& values() const { return image.rgb; }
};
struct GreyRatio {
    const std::vector<float>& grey;
    float operator()(size_t i, int) const { return grey[i]; }
    const std::vector<float>& values() const { return grey; }
};

void checkSize(const Image& texture, size_t ratioValues, size_t perPixel, const char* what) {
    const size_t pixels = static_cast<size_t>(texture.width) * static_cast<size_t>(texture.height);
    if (texture.width < 0 || texture.height < 0 || texture.rgb.size() != pixels * 3 ||
        ratioValues != pixels * perPixel)
        throw std::invalid_argument(
            std::string(what) + ": texture is " + std::to_string(texture.width) + "x" +
            std::to_string(texture.height) + " but the ratio has " + std::to_string(ratioValues) +
            " values, expected " + std::to_string(pixels * perPixel));
}

template <class Ratio>
Image display8(const Image& texture, const Ratio& ratio, int* passes) {
    float maxRatio = 0.0f;
    for (const float r : ratio.values())
        if (!std::isnan(r)) maxRatio = std::max(maxRatio, r);  // NaN ignored
    const int n = multipassCount(maxRatio);
    if (passes) *passes = n;
    Image out(texture.width, texture.height);
    const size_t pixels = out.rgb.size() / 3;
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c)
            out.rgb[i * 3 + static_cast<size_t>(c)] =
                static_cast<float>(
                    framebuffer8(texture.rgb[i * 3 + static_cast<size_t>(c)], ratio(i, c), n)) /
                255.0f;
    return out;
}

template <class Ratio>
Image reference(const Image& texture, const Ratio& ratio) {
    Image out(texture.width, texture.height);
    const size_t pixels = out.rgb.size() / 3;
    for (size_t i = 0; i < pixels; ++i)
        for (int c = 0; c < 3; ++c)
            out.rgb[i * 3 + static_cast<size_t>(c)] =
                singlePassPixel(texture.rgb[i * 3 + static_cast<size_t>(c)], ratio(i, c));
    return out;
}

}  // namespace

Image multipassDisplay8(const Image& texture, const Image& ratio, int* passes) {
    if (ratio.width != texture.width || ratio.height != texture.height)
        throw std::invalid_argument(
            "multipassDisplay8: texture is " + std::to_string(texture.width) + "x" +
            std::to_string(texture.height) + " but the ratio image is " +
            std::to_string(ratio.width) + "x" + std::to_string(ratio.height));
    checkSize(texture, ratio.rgb.size(), 3, "multipassDisplay8");
    return display8(texture, RgbRatio{ratio}, passes);
}

Image multipassDisplay8(const Image& texture, const std::vector<float>& ratio, int* passes) {
    checkSize(texture, ratio.size(), 1, "multipassDisplay8");
    return display8(texture, GreyRatio{ratio}, passes);
}

Image singlePassFloat(const Image& texture, const Image& ratio) {
    if (ratio.width != texture.width || ratio.height != texture.height)
        throw std::invalid_argument("singlePassFloat: texture is " + std::to_string(texture.width) +
                                    "x" + std::to_string(texture.height) +
                                    " but the ratio image is " + std::to_string(ratio.width) + "x" +
                                    std::to_string(ratio.height));
    checkSize(texture, ratio.rgb.size(), 3, "singlePassFloat");
    return reference(texture, RgbRatio{ratio});
}

Image singlePassFloat(const Image& texture, const std::vector<float>& ratio) {
    checkSize(texture, ratio.size(), 1, "singlePassFloat");
    return reference(texture, GreyRatio{ratio});
}

}  // namespace relight
