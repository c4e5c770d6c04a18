// ItemBuffer: what the camera sees, sample by sample: the polygon and the 3D point hit by
// each of `spp` stratified rays per pixel (Embree first-hit queries).
//
// Pixel (x, y) covers image coordinates u in [x - 0.5, x + 0.5], v in [y - 0.5, y + 0.5]
// (the spec's convention: (0, 0) is the centre of the top-left pixel); its samples sit at
// the centres of a k x k grid of sub-pixels (spp = k^2), i.e. a 1-pixel box filter.
// A sample that hits the back of a one-sided polygon, or nothing, has polygon -1.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/scene.h"
#include "radiosity/visibility.h"
#include "relight/io/image.h"
#include "relight/pipeline/camera.h"

namespace relight {

struct ItemBuffer {
    int width = 0, height = 0;
    int spp = 1;                         ///< samples per pixel, a square number
    std::vector<int> polygon;            ///< per sample: polygon index or -1; pixel-major
    std::vector<radiosity::Vec3> point;  ///< per sample: world point hit (metres)

    int sampleIndex(int x, int y, int k) const { return (y * width + x) * spp + k; }
};

/// How densely the preparation samples a photo of a given size.
///
/// The item buffer's samples serve two ends. The display (relight/display/ratio_display.h) needs a
/// few samples per pixel on a small photo, where one pixel covers a large part of a leaf
/// and of a polygon edge; the paper's own display is one sample per screen pixel (Gouraud
/// shading on the graphics hardware, Loscos et al. 2000 §5.3). The estimates from the photo
/// (reflectance, leaf texture, shadow refinement) are means over the photo's samples, whose
/// quality depends on the number of samples on each surface, not on the pixel count.
/// So both are tied to a budget of samples over the whole image, the density of the bundled
/// room at 320x240 and 16 samples per pixel (the default spp):
///  - spp: the largest square <= the requested spp such that spp x pixels <= budget,
///    and at least 1: 16 at 320x240, 4 at 640x480, 1 from 1280x960 on. The image plane is
///    then sampled at least as densely as at 320x240 x 16.
///  - stride: the estimates use the pixels (x, y) with x and y multiples of the stride,
///    the smallest stride whose sub-grid holds at most `budget` samples: 1 up to 1280x960,
///    4 at 4000x3000 (750,000 samples). The direct light of those samples (shadow rays,
///    relight/pipeline/lighting_buffer.h) is the costliest per-sample step of the preparation.
/// A budget of 0 turns both off (spp as requested, stride 1).
constexpr int64_t kDefaultSampleBudget = int64_t{16} * 320 * 240;
struct SamplingPlan {
    int spp = 1;     ///< item-buffer samples per pixel, a square number
    int stride = 1;  ///< pixel stride of the estimates from the photo
};
SamplingPlan planSampling(int width, int height, int spp, int64_t budget);

/// Casts spp rays per pixel (spp is rounded down to a square, at least 1).
ItemBuffer castItemBuffer(const Camera& camera, const radiosity::Scene& scene,
                          const radiosity::Visibility& vis, int spp);

/// The camera's direct importance per polygon of `scene`: 1 where a sample of the item
/// buffer sees it, 0 elsewhere (HierarchicalSolver::setCameraImportance).
std::vector<double> seenPolygons(const ItemBuffer& items, const radiosity::Scene& scene);

}  // namespace relight
