// LightResponses: the hierarchical solution split by light, so that a change of a light's
// colour or strength is a weighted sum rather than a new solution.
//
// With links and subdivision fixed (Loscos et al. 2000, §5.4: an emittance edit keeps them
// and only re-gathers), radiosity is linear in the lights' emittances, channel by channel:
//   B(node) = E(node) + sum_l L_l * R_l(node)
// where L_l is light l's radiance (RGB) and R_l the radiosity that the node reflects when
// light l alone shines with radiance 1 in every channel. A light that had no links (off
// when the links were refined) gets its own first, so every light can be switched on later.
//
// All R_l are found together, by gather/push-pull sweeps over the solver's links that carry
// one value per light (a linear system with one right-hand side per light): the links are
// read once per sweep whatever the number of lights, and the solver's own solution is left
// as it was. (One solve per light, each ending with a re-solve of the photo's lights, was
// most of the preparation of a 200 k-triangle room.)
#pragma once

#include <memory>
#include <span>
#include <vector>

#include "radiosity/solver.h"

namespace radiosity {

class LightResponses {
  public:
    /// Solves for every light's response on `solver`'s links. The solver keeps any light
    /// links this adds; its radiances and solution are unchanged. With `warm` (responses
    /// of the same hierarchy before a small change: new reflectances, scaled light links),
    /// the sweeps start from them, which saves most of them. `warm` is taken, and its
    /// storage becomes the new responses': two sets are never held at once (each is
    /// lights x nodes values, half a GB on a 1.6 M-face model).
    explicit LightResponses(HierarchicalSolver& solver,
                            std::unique_ptr<LightResponses> warm = nullptr);

    int lights() const { return lights_; }
    /// R_l(node) for l = 0..lights()-1: reflected radiosity per unit radiance of light l
    /// (radiosity units per photo unit).
    /// Whether `node` existed when the responses were solved: nodes added since (a virtual
    /// object's or light's, by DynamicObjects) have none.
    bool covers(int node) const {
        return node >= 0 && lights_ > 0 &&
               static_cast<size_t>(node) < R_.size() / static_cast<size_t>(lights_);
    }
    std::span<const Rgb> reflected(int node) const {
        return {R_.data() + static_cast<size_t>(node) * lights_, static_cast<size_t>(lights_)};
    }
    /// Reflected radiosity of `node` for the given radiance of every light:
    /// sum_l radiance[l] * R_l(node).
    Rgb reflected(int node, std::span<const Rgb> radiance) const;
    /// Gather/push-pull sweeps the solve took.
    int sweeps() const { return sweeps_; }

  private:
    int lights_ = 0;
    int sweeps_ = 0;
    std::vector<Rgb> R_;  // [node * lights + l]
};

}  // namespace radiosity
