// LeafTexture: the photo's texture per leaf element (Loscos et al. 2000, §3 step 2 and
// §4.2): for every leaf, the photo samples that fall on it and their mean colour.
//
// The paper reprojects the photo onto each element from the fixed viewpoint; the item
// buffer gives the same correspondence sample by sample (the 3D point each photo sample
// sees). Only samples of "clean" pixels are used (usablePixels): a pixel across a polygon
// edge mixes two surfaces, and one next to a lamp's face carries its glare.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/hierarchy.h"
#include "radiosity/rgb.h"
#include "relight/io/image.h"
#include "relight/pipeline/item_buffer.h"

namespace relight {

/// Per pixel, 1 where the photo value can stand for the surface: finite, every sample on
/// the same reflecting polygon, and no sample of an emitting face within one pixel. With a
/// `stride` above 1 (SamplingPlan in relight/pipeline/item_buffer.h) only the pixels whose x and y
/// are multiples of it can be usable: an even sub-grid of the photo.
std::vector<uint8_t> usablePixels(const ItemBuffer& items, const radiosity::Scene& scene,
                                  const Image& photo, int stride = 1);

class LeafTexture {
  public:
    /// Assigns every usable sample to the leaf of `h` that contains its point.
    LeafTexture(const radiosity::Hierarchy& h, const radiosity::Scene& scene,
                const ItemBuffer& items, const Image& photo, const std::vector<uint8_t>& usable);

    /// Hands a node's samples to its children (call after the node was split), or the
    /// children's back to it (call before its children are removed).
    void split(int node);
    void merge(int node);

    /// Mean photo colour of the leaf's samples (photo units), and their number.
    radiosity::Rgb colour(int node) const;
    int samples(int node) const;
    /// The leaf's samples: item-buffer sample indices (empty for a node with none).
    std::span<const int> sampleIndices(int node) const;
    /// A sample's photo colour and the point it sees.
    radiosity::Rgb sampleColour(int idx) const;
    const radiosity::Vec3& samplePoint(int idx) const {
        return items_.point[static_cast<size_t>(idx)];
    }

  private:
    void ensure(int node);
    const radiosity::Hierarchy& h_;
    const ItemBuffer& items_;
    const Image& photo_;
    std::vector<std::vector<int>> samples_;  ///< by node: sample indices of the item buffer
};

}  // namespace relight
