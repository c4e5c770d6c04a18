// LightResponses: the hierarchical solution split by light, so that a change of a light's
// colour or strength is a weighted sum rather than a new solution.
//
// With links and subdivision fixed (Loscos et al. 2000, §5.4: an emittance edit keeps them
// and only re-gathers), radiosity is linear in the lights' emittances, channel by channel:
//   B(node) = E(node) + sum_l L_l * R_l(node)
// where L_l is light l's radiance (RGB) and R_l the radiosity that the node reflects when
// light l alone shines with radiance 1 in every channel. R_l is found by gather/push-pull
// on the solver's links with only light l on; a light that had no links (off when the
// links were refined) gets its own first, so every light can be switched on later.
#pragma once

#include <span>
#include <vector>

#include "radiosity/solver.h"

namespace radiosity {

class LightResponses {
  public:
    /// Runs one gather/push-pull per light on `solver`'s links, then restores the
    /// solver's light radiances (and re-gathers its own solution). The solver keeps any
    /// light links this adds.
    explicit LightResponses(HierarchicalSolver& solver);

    int lights() const { return lights_; }
    /// R_l(node) for l = 0..lights()-1: reflected radiosity per unit radiance of light l
    /// (radiosity units per photo unit).
    std::span<const Rgb> reflected(int node) const {
        return {R_.data() + static_cast<size_t>(node) * lights_, static_cast<size_t>(lights_)};
    }
    /// Reflected radiosity of `node` for the given radiance of every light:
    /// sum_l radiance[l] * R_l(node).
    Rgb reflected(int node, std::span<const Rgb> radiance) const;

  private:
    int lights_ = 0;
    std::vector<Rgb> R_;  // [node * lights + l]
};

}  // namespace radiosity
