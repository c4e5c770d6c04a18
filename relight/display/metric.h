// The accuracy metric of the scene format (docs/scene-format.md, "Ground truth
// and the accuracy metric"): images reduced to 4x4-pixel block means, blocks kept where
// all 16 pixels are 255 in both masks, then
//   rel_rmse         = sqrt(mean over kept blocks and channels of (R - T)^2) / mean(T)
//   changed_rel_rmse = the same over the kept blocks the edit changes, those where
//                      |T - P| averaged over the channels exceeds 10 % of T averaged
//                      over the channels (undefined when no block changes).
#pragma once

#include <cstdint>
#include <vector>

#include "relight/io/image.h"

namespace relight {

struct Score {
    double relRmse = 0;
    double changedRelRmse = 0;
    bool hasChanged = false;  ///< false: changed_rel_rmse is undefined
    int blocks = 0;           ///< kept blocks
    int changedBlocks = 0;
};

/// sqrt(mean (a - b)^2) / mean(b) over every pixel and channel (no blocks, no masks): how
/// far two renderings of the same thing are apart. 0 when mean(b) is 0 (guard).
/// Throws std::invalid_argument when the sizes differ.
double relativeRmsDifference(const Image& a, const Image& b);

/// R: relit image, T: truth, P: photo, masks of the truth and the photo (255 = keep).
/// All the same size; throws std::invalid_argument otherwise. `errorMap` (optional)
/// receives one pixel per block: the block's RMS error over the channels divided by the
/// mean of T over all kept blocks, in grey; blocks that are not kept are dark blue.
Score scoreImage(const Image& R, const Image& T, const Image& P, const std::vector<uint8_t>& maskT,
                 const std::vector<uint8_t>& maskP, Image* errorMap = nullptr);

}  // namespace relight
