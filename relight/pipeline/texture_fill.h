// Texture filling for real-object removal (Loscos et al. 1999, §4.4 and §5.3): the pixels
// a removed object covered see surfaces the photo never showed there, so their reflectance
// is synthesised from the parts of the same surfaces the photo does show, on the
// reflectance image (lighting divided out, so shadows do not leak into the fill).
//
// The paper feeds a hand-picked sample of each surface to Heeger & Bergen's pyramid
// synthesis. Here the sample is every pixel of the surface near the hole, found through the
// item buffer, and the synthesis is non-parametric sampling (Efros & Leung 1999, the method
// behind Igehy & Pereira's image replacement that the paper follows), with Ashikhmin's
// coherent candidates (2001): structured textures such as floor boards or bricks keep their
// lines, which the histogram matching of a pyramid does not. No Debian library does this
// (OpenCV's inpainting diffuses colour inward, smoothing texture away), hence this file.
//
// Each pixel to fill, from the hole's rim inward (onion peel), takes the value of the
// source pixel whose neighbourhood best matches its own known neighbourhood: the sum of
// squared RGB differences over a (2 radius + 1)^2 window, Gaussian-weighted (sigma =
// radius / 2, Efros & Leung), over the offsets known on both sides. Candidates: for each
// filled neighbour within 2 pixels, the source pixel next to the one it copied (coherence),
// and `randomCandidates` source pixels drawn at random, nearer sources first (the photo's
// perspective shrinks a texture with distance: a nearby source has the right scale).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace relight {

struct TextureFillOptions {
    int radius = 3;             ///< neighbourhood half-width, pixels (7 x 7)
    int randomCandidates = 48;  ///< random source pixels tried per pixel
    uint64_t seed = 0x7e47u;    ///< the random draws (the fill is reproducible)
    /// Pixels per side of the blocks the synthesis works on (1: pixels). A block copies
    /// whole blocks of the sample, at full resolution: on a large photo a texture spans
    /// more pixels, and the window must grow with it (defaultFillBlock).
    int block = 1;
};

/// The block size for a photo of this size: one pixel per 800 pixels of its diagonal, at
/// least 1 (1 at 320 x 240, 2 at 1280 x 960, 6 at 4000 x 3000), so that the window covers
/// the same part of the scene at any resolution, and the work grows as the hole's area over
/// the block's, not as the pixel count.
int defaultFillBlock(int width, int height);

/// What each pixel is to the fill.
enum class FillRole : uint8_t {
    none,    ///< neither read nor written
    source,  ///< its value is a sample of its region's texture
    fill,    ///< to be filled from its region's sources
};

/// An image of `width` x `height` pixels: `value` 3 floats per pixel (read at sources),
/// `region` per pixel (the surface a source shows or a fill pixel now sees; sources fill
/// only pixels of their region), `role` per pixel.
struct TextureFillInput {
    int width = 0, height = 0;
    std::span<const float> value;
    std::span<const int> region;
    std::span<const FillRole> role;
};

struct TextureFillResult {
    std::vector<float> value;  ///< 3 per pixel: the input's, with the fill pixels written
    /// Per pixel: 1 where a fill pixel found no source of its region (value left as the
    /// input's; the caller falls back on the model's reflectance).
    std::vector<uint8_t> unfilled;
    int filled = 0, withoutSource = 0;  ///< counts of fill pixels
};

/// Fills every fill pixel (above). Throws std::invalid_argument when the spans do not
/// match the size.
TextureFillResult fillTexture(const TextureFillInput& in, const TextureFillOptions& options = {});

}  // namespace relight
