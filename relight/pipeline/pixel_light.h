// Direct light per pixel (Loscos et al. 1999, §4.1 and §5): the form factor and visibility
// of every light at the camera's samples, kept per pixel, so that the display divides the
// photo by the light it really received, shadows included, rather than by the light
// interpolated between leaf vertices.
//
// Per pixel p and light l, per unit radiance of l:
//   h_l(p) = pi Gbar_l(p) + sum_v w_v(p) h_l,indirect(v)
// - Gbar_l(p): the mean of G_l (radiosity/direct_light.h: exact point-to-polygon form
//   factor, shadow rays) over the pixel's samples that see a reflecting surface;
// - the indirect part at the leaf vertices, interpolated with the display map's weights
//   (indirect light varies slowly: the hierarchy's, as the paper's B-hat), gathered at
//   each vertex by rays that read the leaves' radiosity where they land
//   (radiosity::rayGatherResponses; RelightOptions::indirectRays).
// The per-pixel display (DisplayMode::pixel, relight/prepared.h) is then
//   pixel = T (sum_l L_l h_l(p) + delta) / (sum_l L_l(photo) h_l(p) + delta),
// Eq. (2) and (4) of the 1999 paper: the reflectance T / H_photo times the new irradiance.
// Real shadows divide out at the pixel, so no shadow removal is needed for it.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/rgb.h"
#include "radiosity/solver.h"
#include "relight/display/ratio_display.h"
#include "relight/pipeline/item_buffer.h"
#include "relight/pipeline/lighting_buffer.h"
#include "relight/pipeline/vertex_lighting.h"

namespace relight {

/// pi Gbar_l(p) for every pixel and light, [pixel * lights + l] (irradiance per unit
/// radiance); 0 for a pixel none of whose samples sees a reflecting surface. From a
/// lighting buffer of every pixel (stride 1), such as the reflectance estimate casts for a
/// photo that is sampled in full: no ray is cast again.
std::vector<float> pixelDirect(const ItemBuffer& items, const radiosity::Scene& scene,
                               const LightingBuffer& buffer);
/// The same, casting the shadow rays of every sample (computeLightingBuffer, stride 1).
std::vector<float> measurePixelDirect(const ItemBuffer& items,
                                      const radiosity::HierarchicalSolver& solver,
                                      radiosity::DirectLightOptions options);

/// What Wen et al.'s display (relight/display/wen_display.h) reads, kept by the preparation
/// with the per-pixel light: each pixel's normal, 3 floats per pixel, the unit mean of the
/// polygon normals of its samples that see a reflecting surface (0 where none does: an
/// emitting face, nothing), as pixelDirect() averages its samples
/// (PreparedImage::pixelNormal); and each light's sky coefficient, k for the component k of
/// an environment light (one of 9), -1 for any other light (PreparedImage::skyCoefficient).
std::vector<float> pixelNormals(const ItemBuffer& items, const radiosity::Scene& scene);
std::vector<int> skyCoefficients(const radiosity::Scene& scene);

/// The indirect part of each vertex's response, h_l(v) - pi G_l(v), [vertex * lights + l]:
/// `lighting` and `direct` as measureVertexLighting() gave them (before real-shadow
/// removal scales the light links).
std::vector<radiosity::Rgb> vertexIndirect(const VertexLighting& lighting,
                                           const VertexDirect& direct);

/// The indirect part of each light's response at pixel px, interpolated over the pixel's
/// vertices with the display map's weights (normalised by their sum), as renderPixelLight()
/// interpolates it: calls part(l, value) for l = 0..L-1. `indirect` is [vertex * L + l].
template <class Part>
void pixelIndirectParts(const DisplayMap& map, size_t px, std::span<const radiosity::Rgb> indirect,
                        size_t L, const Part& part) {
    const int k0 = map.start[px], k1 = map.start[px + 1];
    double wsum = 0;
    for (int k = k0; k < k1; ++k) wsum += static_cast<double>(map.weight[static_cast<size_t>(k)]);
    for (size_t l = 0; l < L; ++l) {
        radiosity::Rgb ind;
        for (int k = k0; k < k1; ++k)
            ind += indirect[static_cast<size_t>(map.vertex[static_cast<size_t>(k)]) * L + l] *
                   (static_cast<double>(map.weight[static_cast<size_t>(k)]) / wsum);
        part(l, ind);
    }
}

/// Whether the per-pixel display draws pixel px: no sample on a lamp's face, none that sees
/// nothing, at least one leaf vertex. The others keep the ratio display's value.
inline bool shownPerPixel(const DisplayMap& map, size_t px) {
    return map.emitterStart[px] == map.emitterStart[px + 1] && !(map.unshaded[px] > 0) &&
           map.start[px] != map.start[px + 1];
}

/// What changed since the photo besides the lamps' radiances (virtual lights and objects,
/// relight/dynamic/dynamic_relighting.h): the direct light per pixel as it is now, for the
/// real lights, then the virtual ones ([pixel * lights + l], pi Gbar per unit radiance),
/// and the indirect irradiance the virtual parts add per vertex (signed, photo units).
struct PixelLightChange {
    std::span<const float> direct;             ///< empty: the photo's (pixelDirect)
    std::span<const radiosity::Rgb> indirect;  ///< per vertex, or empty
};

/// The per-pixel display (above) into `out`, which must hold the ratio display of the same
/// edit: it is left as it is where a pixel sees a lamp's face or has samples that see
/// nothing (the ratio display already shows those as the spec wants), and replaced on the
/// other pixels. `pixelDirect` and `indirect` as above, for the photo's lights;
/// `radianceInPhoto` one per light of the photo, `radianceNow` one per light now (the
/// photo's, then the virtual lights of `change`); `delta` the ratio display's floor
/// (ratioFloor of D), so that both displays guard a vanishing photo irradiance alike.
/// `reflectance` (empty, or 3 floats per pixel): the reflectance merged from all of the
/// scene's photos (pipeline/photo_merge.h); the pixel is then
/// T (H_kept + delta) / (H_photo + delta) + R H_fresh. `pool` (photoPixels of the same
/// photo; null: none) turns on the pooled reflectance below, without a merged reflectance.
void renderPixelLight(const DisplayMap& map, const Image& photo, std::span<const float> pixelDirect,
                      std::span<const radiosity::Rgb> indirect,
                      std::span<const radiosity::Rgb> radianceNow,
                      std::span<const radiosity::Rgb> radianceInPhoto, const radiosity::Rgb& delta,
                      Image& out, PixelLightChange change = {},
                      std::span<const float> reflectance = {}, const PhotoPixels* pool = nullptr);

/// The per-pixel display as a function of one light's direct light alone: the frames of a
/// sun or point lamp being moved (DynamicRelighting::movedLightTerms), which the viewer
/// draws on the GPU from a shadow map (viewer/gpu_moved_light.h). With g the light's unit
/// irradiance at a pixel (its column of PixelLightChange::direct), renderPixelLight()
/// without a merged reflectance is, at a pixel it draws,
///   H = rest + L_m g,   out = max(0, R (max(H, 0) + delta))
///   R = rho                                    where the pool does not apply,
///   R = w rhoPool + (1 - w) pooled[radius(w)]  where lum(H) > kPoolAbove photoLight > 0
/// (pooledPixel(), below: w = kPoolAbove photoLight / lum(H), radius = min(kMaxPoolRadius,
/// round(kPoolRadius / sqrt(w)))).
struct PixelLightTerms {
    int width = 0, height = 0;
    std::vector<float> rest;        ///< 3 per pixel: H_now with light m's direct light at 0
    std::vector<float> rho;         ///< 3 per pixel: T / (max(H_photo, 0) + delta)
    std::vector<float> rhoPool;     ///< 3 per pixel: the pool's (PhotoPixels::rho); 0: none
    std::vector<float> photoLight;  ///< per pixel: lum(H_photo) where the pool applies, else 0
    /// pooledByRadius(): 3 per pixel for each radius from kPoolRadius to kMaxPoolRadius;
    /// null without a pool. It does not depend on the edit: shared by every frame made
    /// from one preparation (GeometryCache::pooledByRadius).
    std::shared_ptr<const std::vector<float>> pooled;
    std::vector<uint8_t> drawn;  ///< per pixel: 1 where renderPixelLight() draws it
    radiosity::Rgb delta;        ///< the ratio display's floor, as renderPixelLight() is given it
    radiosity::Rgb radiance;     ///< L_m: light m's radiance now (radianceNow[m])
};

/// The terms (above) of renderPixelLight()'s image with these arguments, for light `light`
/// (an index into radianceNow). `pooled`: pooledByRadius(map, *pool) when the caller keeps
/// it (null: made here). Throws std::invalid_argument with a merged reflectance (the fresh
/// light is then read through it, not through the photo: not this form) or a light out of
/// range.
PixelLightTerms pixelLightTerms(const DisplayMap& map, const Image& photo,
                                std::span<const float> pixelDirect,
                                std::span<const radiosity::Rgb> indirect,
                                std::span<const radiosity::Rgb> radianceNow,
                                std::span<const radiosity::Rgb> radianceInPhoto,
                                const radiosity::Rgb& delta, PixelLightChange change, int light,
                                std::span<const float> reflectance, const PhotoPixels* pool,
                                std::shared_ptr<const std::vector<float>> pooled = nullptr);

/// One pixel of the terms at unit irradiance g into o[0..2] (what the GPU's shader does;
/// for a pixel drawn per pixel): renderPixelLight()'s value for that g, up to float rounding.
void evalPixelLightTerms(const PixelLightTerms& t, size_t px, double g, float* o);

/// Pooled reflectance where an edit brightens what the photo showed dim (Loscos et al.
/// 1999, §4.2-4.3: where confidence is low, lean on a steadier estimate than the pixel's).
/// A pixel's reflectance T / H_photo carries the photo's noise, which is largest, relative
/// to the value, where the photo is dark; an edit that brightens it by H_now / H_photo shows
/// that noise at the new level. So where H_now > kPoolAbove H_photo (luminance) the pixel
/// shows R H_now with
///   R = w T / H_photo + (1 - w) R_pooled,   w = kPoolAbove H_photo / H_now,
/// R_pooled the mean of T / H_photo over the pixels around it whose reflectance is within
/// kPoolTolerance of its own in every channel (its surface, its texture's colour; its own
/// read as the median of its 3 x 3 neighbourhood, PhotoPixels::guide, so that the pixel's
/// noise does not pick the neighbours that share its error), weighed by
/// their photo light (the ratio of sums for grey light). The pool's half-width is
/// kPoolRadius sqrt(1 / w), at most kMaxPoolRadius: the more the photo's noise is brightened,
/// the wider the mean (2 pixels at 1.5 times the photo's light, 4 at 6 times, 6 from 13.5
/// times on), sampled on a grid of step radius / kPoolRadius, so that a pixel reads about
/// (2 kPoolRadius + 1)^2 others whatever the width.
/// w is the photo's confidence relative to the light shown: 1 up to kPoolAbove (an edit that
/// keeps, dims or slightly brightens the light shows the photo's own pixel), and the pooled
/// estimate takes over as the edit brightens further (half at three times the photo's
/// light). Cornell virtual_light_only 0.0845 -> 0.076, the rooms' virtual lamps 0.0115 ->
/// 0.0112 (bench/RESULTS.md, 2026-11-26); a fixed radius of 4 pools as much noise away on
/// the Cornell box but blurs the rooms' wood and brick where their light changes little
/// (virtual_light_and_box 0.0113 -> 0.0119).
inline constexpr int kPoolRadius = 2;
inline constexpr int kMaxPoolRadius = 6;
inline constexpr double kPoolAbove = 1.5;
inline constexpr double kPoolTolerance = 0.3;
/// What the pooling reads of the photo, per pixel (edit-independent, so made once per
/// prepared state): rho = T / (H_photo + delta) (3 floats) and light = the luminance of
/// H_photo + delta; light 0 where the per-pixel display does not draw the pixel.
PhotoPixels photoPixels(const DisplayMap& map, const Image& photo,
                        std::span<const float> pixelDirect,
                        std::span<const radiosity::Rgb> indirect,
                        std::span<const radiosity::Rgb> radianceInPhoto,
                        const radiosity::Rgb& delta);
/// The photo's irradiance at pixel px as the per-pixel display divides by it: sum_l
/// L_l(photo) (pi Gbar_l(px) + the indirect part interpolated with the display map's
/// weights); 0 for a pixel without vertices. `directPart` (optional) gets the direct terms'
/// sum (pipeline/photo_merge.h weighs a photo by it).
radiosity::Rgb photoIrradianceAt(const DisplayMap& map, size_t px,
                                 std::span<const float> pixelDirect,
                                 std::span<const radiosity::Rgb> indirect,
                                 std::span<const radiosity::Rgb> radianceInPhoto,
                                 radiosity::Rgb* directPart = nullptr);
/// The pooled pixel (above) into o[0..2] when the edit's irradiance `now` (photo units, RGB)
/// is brighter than kPoolAbove times `photoLight`, the luminance of the photo's irradiance
/// H_photo at the pixel; false (o untouched) otherwise. Shared by renderPixelLight() and the
/// fast path (pipeline/pixel_light_table.h). `pooledByRadius` (empty: computed here):
/// R_pooled of every pixel for each radius from kPoolRadius to kMaxPoolRadius,
/// [((radius - kPoolRadius) * pixels + px) * 3 + c], which does not depend on the edit.
bool pooledPixel(const DisplayMap& map, const PhotoPixels& pool, size_t px,
                 const radiosity::Rgb& now, double photoLight, const radiosity::Rgb& delta,
                 float* o, std::span<const float> pooledByRadius = {});
/// That table (above) for every pixel the pool draws (pool.light > 0; 0 elsewhere).
std::vector<float> pooledByRadius(const DisplayMap& map, const PhotoPixels& pool);
/// PhotoPixels::guide of `pool` (W x H pixels): the per-channel median of rho over the
/// drawn pixels of each drawn pixel's 3 x 3 neighbourhood; rho itself where the sizes do
/// not match. photoPixels() sets it.
std::vector<float> poolGuide(int W, int H, const PhotoPixels& pool);
/// R_pooled at pixel px (above).
radiosity::Rgb pooledReflectance(const DisplayMap& map, const PhotoPixels& pool, size_t px,
                                 int radius = kPoolRadius);

}  // namespace relight
