// ReferenceSolver: the classic full-matrix radiosity solution on a uniform mesh, the
// yardstick of the hierarchical solver's convergence studies (Goral et al. 1984; Cohen &
// Wallace 1993, ch. 5).
//
//   B_i = E_i + rho_i sum_j F_ij V_ij B_j   for every element i of a uniform mesh,
//
// F_ij from the same contour-integral form factors (transfer.h) and V_ij from the same
// Embree visibility (shaft test, then a fixed `rays` rays per pair), solved per channel by
// Gauss-Seidel until the largest change is below `tolerance` (relative). Cost: n^2 form
// factors and visibility tests, n^2 floats of memory (n = 4000: 64 MB).
//
// API
//   ReferenceSolver ref(scene, {.maxArea = 0.01, .rays = 16});   // m^2, rays per pair
//   ref.solve();
//   ref.leaves(), ref.radiosityAt(polygon, x)
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "radiosity/detail/transfer.h"
#include "radiosity/hierarchy.h"
#include "radiosity/scene.h"
#include "radiosity/visibility.h"

namespace radiosity {

struct ReferenceOptions {
    double maxArea = 0.01;  ///< elements are subdivided until their area is <= this (m^2)
    int rays = 16;          ///< visibility rays per element pair (when the shaft is not empty)
    int quadratureOrder = 2;
    double tolerance = 1e-7;  ///< Gauss-Seidel stop: max relative change of B in a sweep
    int maxSweeps = 10000;
    std::function<void(const std::string&)> progress;
};

class ReferenceSolver {
  public:
    ReferenceSolver(const Scene& scene, ReferenceOptions options = {});
    ~ReferenceSolver();
    void solve();

    const Hierarchy& hierarchy() const { return h_; }
    const std::vector<int>& leaves() const { return leaves_; }  ///< node ids of the mesh
    Rgb radiosityAt(int polygon, const Vec3& x) const;
    int sweeps() const { return sweeps_; }
    double secondsFormFactors() const { return timeFF_; }
    uint64_t rays() const;

  private:
    Scene scene_;
    ReferenceOptions options_;
    Hierarchy h_;
    std::unique_ptr<Visibility> vis_;
    std::unique_ptr<TransferEvaluator> transfer_;
    std::vector<int> leaves_;
    int sweeps_ = 0;
    double timeFF_ = 0;
};

/// The mean of a solution `B(polygon, x)` over element e (4 x 4 midpoint rule): the
/// reference holds element means, and a finer solution read at one point differs from them
/// wherever B varies inside the element (shadow edges).
Rgb elementMean(const Node& e, const std::function<Rgb(int polygon, const Vec3& x)>& B);

/// Relative RMS difference of radiosity between a solution `B(polygon, x)` and the
/// reference, over the reference's reflecting elements (rho > 0), area-weighted, all three
/// channels:  sqrt(sum A |B - B_ref|^2 / (3 sum A)) / (sum A (B_ref.r + B_ref.g + B_ref.b) /
/// (3 sum A)). Each reference element is compared with elementMean(e, B).
double relativeRmsError(const ReferenceSolver& ref,
                        const std::function<Rgb(int polygon, const Vec3& x)>& B);

}  // namespace radiosity
