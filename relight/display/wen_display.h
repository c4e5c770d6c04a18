// Wen, Liu & Huang 2003 (../shared/seeds/002): a diffuse point of normal n relit by the ratio
// of the new irradiance to the old, I'(n) = I(n) E'(n) / E(n) (their Eq. (13)), with E(n) of
// the sky's 9 coefficients alone, E(n) = sum_k A_l L_k Y_k(n) (their Eq. (15); Ramamoorthi &
// Hanrahan 2001, Eq. 7): nothing occludes the sky and nothing reflects it. DisplayMode::wen
// (`relight render --display wen`) is the per-pixel display (relight/pipeline/pixel_light.h)
// with, for each component k of an environment light, its per-pixel direct light (the
// occluded transfer T_k(p) of radiosity/sky_transfer.h) replaced by A_l Y_k(n(p)), and its
// indirect part by 0; the other lights keep their direct light and bounces. It is kept to
// compare with the occluded transfer the default display uses (bench/display_modes.sh):
// where nothing occludes a point and nothing reflects light to it, both are the same.
#pragma once

#include <span>
#include <vector>

#include "radiosity/rgb.h"
#include "relight/io/image.h"
#include "relight/prepared.h"

namespace relight {

/// A copy of `direct` ([pixel * lights + l], pi Gbar per unit strength, for `lights` lights:
/// the prepared state's first, then any virtual ones) with each sky component's column
/// (p.skyCoefficient[l] = k >= 0, l < p.skyCoefficient.size()) set to A_l Y_k(n) at the
/// pixel's normal, 0 where a pixel has none. Throws std::invalid_argument when p was
/// prepared without per-pixel light or the sizes do not match.
std::vector<float> unoccludedSkyDirect(const PreparedImage& p, std::span<const float> direct,
                                       size_t lights);

/// p.vertexIndirect with the sky components' indirect parts set to 0.
std::vector<radiosity::Rgb> indirectWithoutSky(const PreparedImage& p);

/// DisplayMode::wen for the photo's lights at `radiance` (a light edit): the ratio display
/// where the per-pixel display does not draw, then the per-pixel display of the tables
/// above, its pooled reflectance (pixel_light.h) made from the same tables.
void renderWen(const PreparedImage& p, std::span<const radiosity::Rgb> radiance, Image& out);

}  // namespace relight
