// The per-pixel display's light edit at interactive speed (issue 32: a light edit per pixel
// in <= 1 ms at 320x240 and <= 10 ms at 1280x960 on 2 CPU cores).
//
// renderPixelLight() (pixel_light.h) evaluates per pixel and per light, in double,
//   now = sum_l L_l h_l(p),  H_photo = sum_l L_l(photo) h_l(p),  out = T (now + d) / (H_photo + d)
// with h_l(p) = pi Gbar_l(p) + the indirect part interpolated over the pixel's vertices
// (Loscos et al. 1999, Eq. (2) and (4)). Only the L_l depend on a light edit, so what does not
// is made once per prepared state (pixelLightTable):
//   h[(l * 3 + c) * pixels + p] = h_l,c(p)                  float, one array per light and channel
//   rho[3 p + c]   = T_c / (max(H_photo,c, 0) + d_c)         (H_photo summed in double)
//   photoLight[p]  = luminance of H_photo, the pooled reflectance's threshold (0: not drawn)
// and an edit is, per pixel and channel,
//   now_c = sum_l L_l,c h[l][c][p]          (channels of lights at radiance 0 skipped)
//   out_c = max(0, rho_c (max(now_c, 0) + d_c))
// a contiguous multiply-add over the pixels per light and channel, which the compiler
// vectorises, in chunks of pixels on TBB's threads, into the caller's image (no allocation).
// The pooled reflectance (pixel_light.h) is applied where the edit brightens the photo's light
// by more than kPoolAbove, by the same function as the reference path.
// The photo's own radiances give the photo back bit for bit (ratio exactly 1: out = max(T, 0)).
// Float sums of at most a few tens of terms: equal to renderPixelLight() to about 1e-6
// relative (tests/relight/pixel_light_table_test.cpp).
#pragma once

#include <span>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/display/ratio_display.h"
#include "relight/io/image.h"

namespace relight {

struct PixelLightTable {
    size_t pixels = 0, lights = 0;
    std::vector<float> h;            ///< [(l * 3 + c) * pixels + p]: h_l,c(p); 0 where not drawn
    std::vector<float> rho;          ///< [3 p + c]: T / (H_photo + delta); 0 where not drawn
    std::vector<float> photoLight;   ///< [p]: luminance of H_photo; 0 where not drawn
    std::vector<int> ratioPixels;    ///< the pixels the per-pixel display does not draw
    std::vector<int> ratioVertices;  ///< the vertices those pixels read, each once
    /// R_pooled per radius (pixel_light.h, pooledByRadius): the pool's mean does not depend
    /// on the edit, only its radius does; empty without a pool.
    std::vector<float> pooled;
    radiosity::Rgb delta;  ///< ratioFloor(D), as renderPixelLight() is given it
    bool empty() const { return h.empty(); }
};

/// The table of an image prepared with per-pixel light (arguments as photoPixels() in
/// pixel_light.h, and `pool` its photoPixels(), or null); empty without per-pixel light, or
/// above kMaxPixelTransfers floats of h.
PixelLightTable pixelLightTable(const DisplayMap& map, const Image& photo,
                                std::span<const float> pixelDirect,
                                std::span<const radiosity::Rgb> indirect,
                                std::span<const radiosity::Rgb> radianceInPhoto,
                                const radiosity::Rgb& delta, const PhotoPixels* pool);

/// The per-pixel display of `radianceNow` (one radiance per light of the photo, no virtual
/// part, no merged reflectance) into `out` (resized to the map's size if it is not): every
/// pixel is written, those the per-pixel display does not draw (table.ratioPixels) with a
/// value the caller replaces by the ratio display's (ratioPixel). `pool` as
/// renderPixelLight's.
void renderPixelLightFast(const PixelLightTable& table, const DisplayMap& map, const Image& photo,
                          std::span<const radiosity::Rgb> radianceNow,
                          std::span<const radiosity::Rgb> radianceInPhoto, Image& out,
                          const PhotoPixels* pool);

}  // namespace relight
