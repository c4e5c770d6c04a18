// The camera samples that the overlay of virtual parts and removed objects casts again
// (relight/dynamic/dynamic_relighting.h, object_removal.h): a regular k x k grid in each
// pixel, k = floor(sqrt(spp)) (at least 1) for the item buffer's spp. Both read the same
// sample s of a pixel: the removal's fill is stored per sample and the overlay looks it up.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

namespace relight {

struct OverlaySamples {
    int k = 1;  ///< samples per side of a pixel

    explicit OverlaySamples(int spp)
        : k(std::max(1, static_cast<int>(std::floor(std::sqrt(static_cast<double>(spp)))))) {}
    int count() const { return k * k; }
    /// Image position (u, v) of sample s of pixel (x, y): (0, 0) is the centre of the
    /// top-left pixel (the spec's convention).
    std::pair<double, double> at(int x, int y, int s) const {
        return {x - 0.5 + ((s % k) + 0.5) / k, y - 0.5 + ((s / k) + 0.5) / k};
    }
};

}  // namespace relight
