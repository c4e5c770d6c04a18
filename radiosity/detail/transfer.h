// Transfer: the unoccluded transfer coefficient F and the visibility V of a link between
// two nodes of the hierarchy, and the refinement oracle's conservative bound on F.
//
// Element -> element: F = F_{r -> s}, Lambert's contour integral from the receiver's
// quadrature points to the source polygon (form_factor.h). Every link of a receiver uses
// the same points, so in a closed enclosure the links of one receiver sum to 1 exactly.
//
// Links with a cluster end use bounded estimates (Sillion 1995, with the bounds of Smits,
// Arvo & Greenberg 1994). With w the unit direction from the receiver's centre to the
// source's, d the distance between the centres and A_s = projectedArea(s, -w) the area of
// the source's surfaces facing the receiver, projected (hierarchy.h: exact for an element,
// bounded by the cluster's box cross-section), the source is replaced by a disc of that
// area facing the receiver, whose exact on-axis form factor is (discFormFactor)
//     F_perp = A_s / (pi d^2 + A_s)  <=  1.
//   element r <- any s:   F = max(0, n_r . w) F_perp     (the receiver's cosine)
//   cluster r <- any s:   F = F_perp; the gather bins B_s F V by its direction w in the
//                         cluster's directional irradiance, and each surface inside takes
//                         it by its own normal (directional_irradiance.h), so that no
//                         surface facing away is lit.
// Each transfer is thus at most what a surface facing the source squarely could gather
// from a disc of the source's projected area, finite at any distance (no 1/d^2 blow-up
// when clusters touch). What no per-link bound can ensure -- that the links of one
// receiver, unoccluded estimates of sources that may hide each other, sum to at most 1 --
// the solver enforces per leaf (HierarchicalSolver's energy bound).
//
// The oracle's bound for a link with a cluster end is conservative: the source's projected
// area at the distance between the bounding spheres, A_s / (pi d_min^2), capped at 1 (a
// form factor cannot exceed 1), and 1 when the spheres overlap.
//
// Both the estimate and the oracle's bound of a link with a cluster end are also capped by
// the normal-cone bound (coneBound): when every surface of the two nodes faces within an
// angle alpha of one direction n (the two normal cones about their bisector), light only
// crosses between them along directions w that both ends face, n.w > -delta at the
// receiver and n.w < delta at the source, delta = 2 sin(alpha / 2) = |n_x - n|: a band
// of solid angle 4 pi delta about n's horizon, in which each receiving cosine n_x.w is
// below 2 delta. So from any receiving point F <= (4 pi delta)(2 delta) / pi = 8 delta^2,
// at any distance. Two neighbouring patches of one wall (a reconstruction's bumpy
// triangles, within a few degrees of the wall's plane) exchange at most a few percent of
// their light; with spheres that touch, the distance bound would say 1 and have them
// refined down to the triangles, each pair with its own rays.
//
// Visibility (Loscos et al. 2000, §2.3): first a shaft between the two bounding boxes
// (Haines & Wallace 1991) is tested against the cluster hierarchy; if it holds no other
// polygon the link is VISIBLE without rays. Otherwise rays join stratified points of the
// two nodes: `minRays` first; if they disagree (penumbra) up to `maxRays` in all. All rays
// blocked gives INVISIBLE, all free VISIBLE, else PARTIAL with V the free fraction.
// Sample points come from a generator seeded by the two node ids, so results do not
// depend on the order in which links are evaluated or on the thread count.
//
// Narrowed sources (solve()'s rounds, SolverOptions::narrowClusterSources, off by default:
// solver.h says why): a cluster sends the area mean of its surfaces'
// radiosity, the turned-away ones' too. A lamp shade of thin sheets, its inside bright and
// its outside dark, then lights the room through its outside: the rays end on the outer
// faces that face the receiver, yet the link carries the inner faces' mean as well (8.4 %
// of a shaded lamp's power left a closed shade, bench/shaded_lamp). So a VISIBLE link from
// a cluster whose rays were cast gathers from the narrowest node under the cluster that
// holds every end of its rays and every part whose normal cone does not prove it turned
// away from the receiver, with F V kept: the same transfer under a uniform radiosity, the
// radiosity of the part that faces the receiver otherwise (6.2 % left the shade; 4.6 %
// narrowed to the rays' ends alone, which lost 2 % of a closed room's light). PARTIAL
// links are not narrowed (transfer.cpp says why).
#pragma once

#include <atomic>
#include <cstdint>

#include "radiosity/defaults.h"
#include "radiosity/hierarchy.h"
#include "radiosity/link.h"
#include "radiosity/visibility.h"

namespace radiosity {

struct TransferOptions {
    int quadratureOrder = 2;        ///< Gauss points per direction on a receiving element (1..16)
    int minRays = kDefaultMinRays;  ///< rays of the first visibility round, 1..256
    int maxRays = kDefaultMaxRays;  ///< rays in all in penumbra, >= minRays (typ. 16..64)
    bool useShafts = true;          ///< skip rays when the shaft holds no occluder
};

/// Counters, reported as "Category/Name".
struct TransferCounters {
    std::atomic<uint64_t> formFactors{0};  ///< "Links/FormFactors": F evaluations
    std::atomic<uint64_t> shaftTests{0};   ///< "Shafts/Tests"
    std::atomic<uint64_t> shaftEmpty{0};   ///< "Shafts/Empty": links decided without rays
    std::atomic<uint64_t> rays{0};         ///< "Visibility/Rays" cast for links
};

/// Unit direction from R's centre to S's (zero when they coincide): the direction a
/// cluster receiver's vector irradiance takes from the link R <- S.
Vec3 linkDirection(const Node& R, const Node& S);
/// Bounded estimate of the form factor from point x (unit normal n) to a node S seen from
/// afar: discFormFactor(max(0, n.w), 1, d^2, h.projectedArea(S, -w)), the same estimate as a
/// link's for an element receiver (used by per-point gathers through cluster sources).
double pointToNode(const Hierarchy& h, const Vec3& x, const Vec3& n, const Node& S);

class TransferEvaluator {
  public:
    TransferEvaluator(const Hierarchy& h, const Visibility& vis, TransferOptions options)
        : h_(h), vis_(vis), options_(options) {}

    /// The normal-cone bound on F between r and s (see above): 8 delta^2, at most 1.
    double coneBound(int r, int s) const;
    /// False when no light can go from s to r: an element source entirely behind the
    /// receiver element's plane, or a receiver entirely behind the source element's plane
    /// (one-sided surfaces). Clusters are treated as facing every way.
    bool facing(int r, int s) const;
    /// Unoccluded transfer coefficient F of the link r <- s (see above).
    double formFactor(int r, int s) const;
    /// Conservative bound on F used by the refinement oracle: formFactor() for two
    /// elements, min(1, A_s / (pi d_min^2), coneBound) (1 when the spheres overlap) when
    /// one end is a cluster.
    double bound(int r, int s, double F) const;
    /// The area of receiver r that intercepts what it gathers from s (m^2), for the
    /// oracle's power estimate rho B F A: an element's area, or a cluster's area facing
    /// the source, projected (projectedArea).
    double receiverArea(int r, int s) const;
    /// Fills V, type, rays and shaftEmpty of `link`. `thorough` casts all maxRays at
    /// once: used where a verdict of INVISIBLE would stop refinement, so that it rests on
    /// maxRays blocked rays rather than on the first few. `narrow`: a VISIBLE link from a
    /// cluster whose rays were cast then gathers from the narrowest node under it that
    /// holds the ends of its rays, with the same F V (narrowSource; "Narrowed sources").
    void visibility(Link& link, bool thorough = false, bool narrow = false) const;
    /// True when the shaft between r and s holds no polygon other than theirs.
    bool shaftIsEmpty(int r, int s) const;
    /// Whether visibility() tests a link's shaft before its rays (with options().useShafts;
    /// on until turned off). HierarchicalSolver::solve turns the tests off for the rest of
    /// a solve once they found almost no shaft empty. Not while visibility() runs.
    void setShaftTests(bool on) { shaftTests_ = on; }
    bool shaftTests() const { return shaftTests_; }

    const TransferOptions& options() const { return options_; }
    mutable TransferCounters counters;

  private:
    void narrowSource(Link& link, int lo, int hi) const;
    /// True when every surface of c faces away from every point of r's box (its normal
    /// cone against the directions between the two boxes): c sends r nothing.
    bool turnedAway(int r, int c) const;
    bool shaftQuery(const class Shaft& shaft, int node, int skipA, int skipB,
                    const Bounds3& box) const;
    const Hierarchy& h_;
    const Visibility& vis_;
    TransferOptions options_;
    bool shaftTests_ = true;
};

}  // namespace radiosity
