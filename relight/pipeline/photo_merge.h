// Reflectance from all of a scene's photos, per pixel (Loscos et al. 1999, §4.1-4.3, Eq. (3)).
//
// Every photo of a scene is taken from the same camera under its own lamps S_i (scene.json's
// "lights_on"). With the per-pixel light of the display (pipeline/pixel_light.h), photo i's
// irradiance at surface pixel p is
//   H_i(p) = sum_{l in S_i} L_l (pi Gbar_l(p) + sum_v w_v h_l,ind(v)),
// and T_i(p) / H_i(p) is its reading of the reflectance over pi there. Eq. (3) merges the
// readings weighed by confidence:
//   R(p) = sum_i K_i(p) T_i(p) / (H_i(p) + delta) / sum_i K_i(p)
// with K_i(p) = E_i (E_i / H_i), E_i the luminance of the direct part of H_i(p) and H_i its
// whole (irradiance units), and the paper's filters:
// - light ratio: a photo counts in proportion to the light its lamps send straight to the
//   pixel, where the model's light is exact (form factors, shadow rays) and the photo's value
//   far above its noise, and more where that is most of its light (E_i / H_i); a pixel lit
//   only indirectly in photo i gets K_i = 0;
// - shadow boundaries: K_i = 0 at a pixel whose direct light in photo i differs from a
//   neighbour's by more than half (kBoundaryContrast): there the model's shadows and the
//   photo's are most apt to be a pixel apart;
// - pixel value: K_i = 0 where T_i is not finite or is negative in a channel.
// The display reads the edit's light as
//   pixel = max(0, T_0 (H_kept + delta) / (H_0 + delta) + R H_fresh)
// H_kept: the light of the first photo's lamps at their new radiance, read through the first
// photo (its noise then scales with its light: a lamp switched off takes its share of the
// noise with it); H_fresh: the light the first photo did not hold (lamps off in it, virtual
// lamps, what virtual objects change), read with R. With R = T_0 / (H_0 + delta) this is
// the per-pixel display of the first photo alone, and for the photo's own lighting it is
// the first photo whatever R.
// Measured on room-multi (bench/RESULTS.md, 2026-11-25): better where the fresh light is a
// lamp photographed alone (lamp_M3_on 0.0158 -> 0.0121: photo_M3 shows its light), worse for
// a virtual lamp (0.0108 -> 0.0156): the single-lamp photos read reflectances 0.5-4 % below
// the first photo's, so RelightOptions::mergePhotos is off by default.
#pragma once

#include <span>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/display/ratio_display.h"
#include "relight/io/image.h"

namespace relight {

/// One photo for the merge: its pixels (linear) and the radiance of every light in it (0 for
/// a lamp that is off), one per light of the per-pixel light.
struct MergePhoto {
    const Image* image = nullptr;
    std::vector<radiosity::Rgb> radiance;
};

/// Neighbouring pixels whose direct light differs by more than this share of the larger are
/// a shadow boundary (dimensionless).
inline constexpr double kBoundaryContrast = 0.5;

struct PhotoMerge {
    /// R per pixel, 3 floats (reflectance over pi, per unit irradiance); 0 where the
    /// per-pixel display does not show the pixel (a lamp's face, samples that see nothing).
    std::vector<float> reflectance;
    int pixels = 0;              ///< surface pixels merged
    double firstPhotoShare = 0;  ///< mean share of the first photo's K in those pixels
};

/// R above. photos[0] is the first photo (the display's T_0). `pixelDirect` and `indirect` as
/// the PreparedImage holds them; `delta` the display's floor (ratioFloor of D). Throws
/// std::invalid_argument when the sizes do not match.
PhotoMerge mergePhotos(const DisplayMap& map, std::span<const MergePhoto> photos,
                       std::span<const float> pixelDirect, std::span<const radiosity::Rgb> indirect,
                       const radiosity::Rgb& delta);

}  // namespace relight
