// What the relit photo shows where real objects were taken out (Loscos et al. 1999, §4.4,
// §5.3). The solver has the objects out (radiosity::HierarchicalSolver::removeRealObject):
// their shadows go through the display as any change of light does. Their pixels need more:
//  1. the mask: the pixels with an item-buffer sample on a removed object, grown by
//     `grow` pixels into the surfaces it revealed ("we extend the weight mask a few pixels
//     to compensate for inaccuracies in the removed object geometry");
//  2. the camera's samples in the mask cast again (the item buffer's update), the objects
//     hidden: each sample's surface, point and leaf now;
//  3. the reflectance there: each pixel's surface (surfaceOf) textured from the pixels of
//     the same surface the photo shows nearby, on the reflectance image
//     R(p) = T(p) / H_photo(p) (radiance per unit irradiance: rho / pi), by texture
//     synthesis (pipeline/texture_fill.h); the leaf's reflectance / pi where the photo
//     shows none of the surface;
//  4. the irradiance at each sample: the direct light of every light (shadow rays, the
//     edit's radiances) and the indirect light interpolated at the sample's leaf.
// Around the objects (a ring from the mask's edge, as wide as half their extent in the photo)
// the pixels keep the photo's reflectance, T / H_photo as the display reads it, but are lit as the
// revealed ones (direct light by shadow rays and indirect light gathered at their points, the
// objects out). The display's indirect change there is interpolated from vertex changes measured
// through the links that ran to the object's faces, and read up to 1.6 times the truth's light
// beside a cabinet (bench/RESULTS.md, 2026-11-26, third session). A mask pixel then shows R(p)
// times the mean irradiance of its samples that see a reflecting surface, plus the radiance of
// those that see a lamp's face (DynamicRelighting::overlay(): the pixel is replaced whole).
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/rgb.h"
#include "radiosity/vec.h"
#include "relight/dynamic/rectified_fill.h"
#include "relight/relighting.h"

namespace relight {

struct RemovedRegion {
    int x0 = 0, y0 = 0, width = 0, height = 0;  ///< the mask's box, pixels
    int k = 1;                                  ///< samples per pixel: k x k, stratified
    std::vector<char> mask;                     ///< per box pixel: replaced by the fill
    std::vector<char> covered;       ///< per box pixel: an item-buffer sample on a removed object
    std::vector<float> reflectance;  ///< 3 per box pixel: R (above)
    /// Per box pixel and sample ([pixel * k * k + s]): the polygon now seen (-1: none),
    /// the point, the scene leaf, and the direct irradiance at the edit's radiances.
    std::vector<int> polygon, leaf;
    std::vector<radiosity::Vec3> point;
    std::vector<radiosity::Rgb> direct;
    /// Per box pixel and real light ([pixel * lights + l]): the indirect irradiance per
    /// unit radiance of light l, gathered by rays at the revealed points with the objects
    /// out (radiosity::rayGatherResponses), smoothed along the surface. The display's vertex
    /// indirect light cannot serve there: its vertices under the object gathered the
    /// object's faces (the room's cabinet corner read 1.7 times its light). Empty when
    /// prepared without per-pixel light: then the leaf's vertex light is read.
    std::vector<radiosity::Rgb> indirect;
    int lights = 0;                 ///< real lights in `indirect`
    std::vector<uint8_t> gathered;  ///< per box pixel: 1 where `indirect` holds a gather
    int filled = 0, modelled = 0;   ///< mask pixels textured from the photo, from the model
    int ring = 0;                   ///< mask pixels around the objects: the photo's reflectance

    bool empty() const { return width <= 0 || height <= 0; }
    bool inMask(int x, int y) const {
        return x >= x0 && y >= y0 && x < x0 + width && y < y0 + height &&
               mask[static_cast<size_t>((y - y0) * width + (x - x0))] != 0;
    }
};

/// The mask's growth for a photo: one pixel per 400 pixels of its diagonal, at least one
/// (1 at 320 x 240, 13 at 4000 x 3000): a calibration error of a fixed angle covers more
/// pixels on a larger photo.
int defaultMaskGrowth(int width, int height);

/// Steps 1-3 above for the objects `removed` (indices of the solver's scene objects),
/// which must be out of the solver already. `realNodes`: the scene's node count (leaves
/// below it are the scene's). Empty when nothing of them is in the photo.
RemovedRegion buildRemovedRegion(const Relighting& r, const std::vector<int>& removed,
                                 size_t realNodes, int grow,
                                 SurfaceSynthesis synthesis = SurfaceSynthesis::exemplar);

/// Step 4's direct light at the region's samples for the lights' radiances (the real lights,
/// then the virtual ones, solver order); only at the samples whose leaf is marked in
/// `changedLeaves` when given (by node id), at all of them otherwise.
void measureRegionDirect(RemovedRegion& region, const Relighting& r,
                         std::span<const radiosity::Rgb> radiance,
                         const std::vector<char>* changedLeaves = nullptr);

}  // namespace relight
