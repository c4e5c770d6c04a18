// Transfer: the unoccluded transfer coefficient F and the visibility V of a link between
// two nodes of the hierarchy, and the refinement oracle's conservative bound on F.
//
// Element -> element: F = F_{r -> s}, Lambert's contour integral from the receiver's
// quadrature points to the source polygon (form_factor.h). Every link of a receiver uses
// the same points, so in a closed enclosure the links of one receiver sum to 1 exactly.
//
// Links with a cluster end use Sillion's isotropic cluster (Sillion 1995): a cluster of
// total surface area A emits as if its surfaces faced every direction equally, with
// projected area A/4 (the mean of max(0, cos) over the sphere), and distributes the
// irradiance it receives equally to its contents, each absorbing 1/4 of the perpendicular
// irradiance on average. With d the distance between the two centres:
//   element r <- cluster s: F = A_s cos_r / (4 pi d^2)
//   cluster r <- element s: F = A_s cos_s / (4 pi d^2)
//   cluster r <- cluster s: F = A_s / (16 pi d^2)
// Energy is conserved on average over orientations, not per element: the oracle refines
// every cluster link that carries a significant share of the power.
//
// The oracle's bound for a cluster end is conservative: cos <= 1 and the distance between
// the bounding spheres, F <= A_s / (pi d_min^2), infinite when the spheres overlap, so
// that no cluster link is kept between overlapping volumes.
//
// Visibility (Loscos et al. 2000, §2.3): first a shaft between the two bounding boxes
// (Haines & Wallace 1991) is tested against the cluster hierarchy; if it holds no other
// polygon the link is VISIBLE without rays. Otherwise rays join stratified points of the
// two nodes: `minRays` first; if they disagree (penumbra) up to `maxRays` in all. All rays
// blocked gives INVISIBLE, all free VISIBLE, else PARTIAL with V the free fraction.
// Sample points come from a generator seeded by the two node ids, so results do not
// depend on the order in which links are evaluated or on the thread count.
#pragma once

#include <atomic>
#include <cstdint>

#include "radiosity/hierarchy.h"
#include "radiosity/link.h"
#include "radiosity/visibility.h"

namespace radiosity {

struct TransferOptions {
    int quadratureOrder = 2;  ///< Gauss points per direction on a receiving element (1..16)
    int minRays = 4;          ///< rays of the first visibility round, 1..256 (typ. 4)
    int maxRays = 16;         ///< rays in all for a link in penumbra, >= minRays (typ. 16..64)
    bool useShafts = true;    ///< skip rays when the shaft holds no occluder
};

/// Counters, reported as "Category/Name".
struct TransferCounters {
    std::atomic<uint64_t> formFactors{0};  ///< "Links/FormFactors": F evaluations
    std::atomic<uint64_t> shaftTests{0};   ///< "Shafts/Tests"
    std::atomic<uint64_t> shaftEmpty{0};   ///< "Shafts/Empty": links decided without rays
    std::atomic<uint64_t> rays{0};         ///< "Visibility/Rays" cast for links
};

class TransferEvaluator {
  public:
    TransferEvaluator(const Hierarchy& h, const Visibility& vis, TransferOptions options)
        : h_(h), vis_(vis), options_(options) {}

    /// False when no light can go from s to r: an element source entirely behind the
    /// receiver element's plane, or a receiver entirely behind the source element's plane
    /// (one-sided surfaces). Clusters are treated as facing every way.
    bool facing(int r, int s) const;
    /// Unoccluded transfer coefficient F of the link r <- s (see above).
    double formFactor(int r, int s) const;
    /// Conservative bound on F used by the refinement oracle: formFactor() for two
    /// elements, A_s / (pi d_min^2) (or +inf) when one end is a cluster.
    double bound(int r, int s, double F) const;
    /// Fills V, type, rays and shaftEmpty of `link`. `thorough` casts all maxRays at
    /// once: used where a verdict of INVISIBLE would stop refinement, so that it rests on
    /// maxRays blocked rays rather than on the first few.
    void visibility(Link& link, bool thorough = false) const;
    /// True when the shaft between r and s holds no polygon other than theirs.
    bool shaftIsEmpty(int r, int s) const;

    const TransferOptions& options() const { return options_; }
    mutable TransferCounters counters;

  private:
    bool shaftQuery(const class Shaft& shaft, int node, int skipA, int skipB,
                    const Bounds3& box) const;
    const Hierarchy& h_;
    const Visibility& vis_;
    TransferOptions options_;
};

}  // namespace radiosity
