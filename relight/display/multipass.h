// Multi-pass display of display ratios above 1 (Loscos et al. 2000, §5.3, Fig. 19).
//
// Each pixel of the relit image is T * B/D: the texture T (the photo, 8-bit) modulated by
// the display ratio B/D of its element, which exceeds 1 where the illumination increased
// (a virtual light, a brighter source). OpenGL's fixed function clamps glColor to [0, 1],
// so a single GL_MODULATE pass shows T * min(B/D, 1) and the brightening is lost. The
// paper draws the scene n = ceil(max B/D) times with additive blending
// (glBlendFunc(GL_ONE, GL_ONE)); pass k = 0 .. n-1 modulates the texture by the vertex
// colour clamp(B/D - k, 0, 1). The passes sum to T * B/D, up to the 8-bit quantization of
// each pass and the saturation of the framebuffer at 1.
//
// These are the CPU reference functions of the fixed-function pipeline (linear unorm8
// texture and framebuffer); the viewer uses multipassCount() and draws the same passes on
// the GPU in an sRGB 8-bit target (viewer/gpu_display.h), tested against its own float
// display. The 8-bit emulation follows the fixed-function pipeline:
//   t8 = round(255 clamp(t, 0, 1))                 texture texel (unorm8)
//   c8 = round(255 passModulation(r, k))           vertex colour (unorm8)
//   p8 = round(t8 c8 / 255)                        GL_MODULATE, rounded to 8 bits
//   fb = min(255, fb + p8)                         GL_ONE, GL_ONE blend, saturating
// Passes whose modulation is 0 or 1 are exact (p8 = 0 or t8), so only the one pass with a
// fractional modulation rounds the colour and the product. Before saturation the result
// is within (1 + r/2) / 255 of t r for r <= kMaxPasses: 1/2 step for the product, at most
// 1/2 step for the colour (times t8/255 <= 1), and r times 1/2 step for the texel;
// min(1, .) does not increase the error (tests/relight/multipass_test.cpp).
//
// Out-of-range input: texture values are clamped to [0, 1] (NaN -> 0), as an 8-bit texture
// upload would; a NaN or negative ratio modulates nothing (black, 1 pass); ratios above
// kMaxPasses (+Inf included) are CLAMPED to kMaxPasses: multipassCount never returns more
// than kMaxPasses, and the 8-bit emulation draws at most kMaxPasses passes. The float
// reference singlePassFloat does not cap the ratio.
#pragma once

#include <cstdint>
#include <vector>

#include "relight/io/image.h"

namespace relight {

/// Cap on the number of passes (and on the ratio the 8-bit display can show): 64 passes is
/// 6 stops of brightening, beyond which a relit room is white anyway.
inline constexpr int kMaxPasses = 64;

/// Passes needed for the largest ratio of the scene: max(1, ceil(maxRatio)), so 1 pass when
/// no ratio exceeds 1. NaN or negative -> 1; above kMaxPasses (+Inf included) -> kMaxPasses.
int multipassCount(float maxRatio);

/// Vertex colour of pass `pass` (0-based): clamp(ratio - pass, 0, 1); NaN ratio -> 0.
/// Over passes 0 .. n-1 these sum to the ratio exactly for ratios in [0, n].
float passModulation(float ratio, int pass);

/// unorm8 conversion: round(255 clamp(v, 0, 1)); NaN -> 0.
std::uint8_t quantize8(float v);

/// GL_MODULATE of two 8-bit values: round(texel * colour / 255).
std::uint8_t modulate8(std::uint8_t texel, std::uint8_t colour);

/// The 8-bit framebuffer after drawing `passes` passes (1 .. kMaxPasses, clamped to that
/// range) of texture value `texture` modulated by `ratio`: sum over k < passes of
/// modulate8(quantize8(texture), quantize8(passModulation(ratio, k))), saturating at 255.
/// passes = 1 is the plain single-pass display, which clips the ratio at 1.
std::uint8_t framebuffer8(float texture, float ratio, int passes);

/// framebuffer8 with the passes the ratio needs, multipassCount(ratio).
std::uint8_t multipassPixel8(float texture, float ratio);

/// The float reference of one pixel: clamp(t, 0, 1) * ratio clipped to [0, 1] (a NaN or
/// negative ratio counts as 0).
float singlePassPixel(float texture, float ratio);

/// Multi-pass display of a whole image. `texture`: linear values in [0, 1]; `ratio`: B/D
/// per pixel and channel (same size as the texture). The number of passes is
/// multipassCount of the largest ratio in the image (NaN ignored), stored in `*passes` when
/// given. Returns the 8-bit framebuffer as values k/255. Throws std::invalid_argument when
/// the sizes differ.
Image multipassDisplay8(const Image& texture, const Image& ratio, int* passes = nullptr);

/// The same with one grey ratio per pixel (width * height values, row-major from the
/// top-left), applied to all three channels.
Image multipassDisplay8(const Image& texture, const std::vector<float>& ratio,
                        int* passes = nullptr);

/// The float single-pass reference of a whole image: singlePassPixel per pixel and channel.
/// Throws std::invalid_argument when the sizes differ.
Image singlePassFloat(const Image& texture, const Image& ratio);

/// The same with one grey ratio per pixel.
Image singlePassFloat(const Image& texture, const std::vector<float>& ratio);

}  // namespace relight
