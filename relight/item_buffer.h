// ItemBuffer: what the camera sees, sample by sample: the polygon and the 3D point hit by
// each of `spp` stratified rays per pixel (Embree first-hit queries).
//
// Pixel (x, y) covers image coordinates u in [x - 0.5, x + 0.5], v in [y - 0.5, y + 0.5]
// (the spec's convention: (0, 0) is the centre of the top-left pixel); its samples sit at
// the centres of a k x k grid of sub-pixels (spp = k^2), i.e. a 1-pixel box filter.
// A sample that hits the back of a one-sided polygon, or nothing, has polygon -1.
#pragma once

#include <vector>

#include "radiosity/scene.h"
#include "radiosity/visibility.h"
#include "relight/camera.h"
#include "relight/image.h"

namespace relight {

struct ItemBuffer {
    int width = 0, height = 0;
    int spp = 1;                         ///< samples per pixel, a square number
    std::vector<int> polygon;            ///< per sample: polygon index or -1; pixel-major
    std::vector<radiosity::Vec3> point;  ///< per sample: world point hit (metres)

    int sampleIndex(int x, int y, int k) const { return (y * width + x) * spp + k; }
};

/// Casts spp rays per pixel (spp is rounded down to a square, at least 1).
ItemBuffer castItemBuffer(const Camera& camera, const radiosity::Scene& scene,
                          const radiosity::Visibility& vis, int spp);

}  // namespace relight
