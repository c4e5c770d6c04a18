// Final gather: the indirect irradiance at a point, gathered through the links of the
// element that holds it (and of every node above it) with the form factor taken from the
// point itself rather than averaged over the element.
//
// The hierarchical solution is piecewise constant: one B per leaf element. Shown as is, it
// draws the element grid on every wall, and it misses how light from a neighbouring wall
// rises towards a shared corner inside one element. Re-evaluating the transfer of each
// link at the shaded point (Lischinski, Tampieri & Greenberg 1993; Smits, Arvo & Greenberg
// 1994, "final gather") removes both, at no cost in rays: a link's visibility V is reused.
//
// For a link r <- s on the chain above the leaf holding x (normal n):
//   element s:  F(x) = pointToPolygon(x, n, s)                (Lambert's contour integral);
//               where F(x) > 0.05 (x close to s) s's children are used, each with its
//               own B and F(x), recursively: a link is accepted for the receiving element
//               as a whole, and a point near the source's edge sees its B vary
//   cluster s:  F(x) = A_s max(0, n.w) / (4 pi d^2)           (isotropic cluster, Sillion
//               1995, with the receiver's cosine taken at x; w, d: direction and distance
//               from x to the cluster's centre)
//   H_indirect(x) = sum over links of (B_s - E_s) F(x) V(x)
// (an emitter's emission E_s is direct light; what it reflects, if anything, is not).
// V(x) is the link's V where the link is VISIBLE or INVISIBLE. A PARTIAL link's V is an
// average over the receiving element: kept as is, it paints the element grid into the
// indirect light next to every occluder (a floor beside a block). There V(x) is measured
// from x itself with `partialRays` rays to stratified points of the source (0 keeps V).
// Direct light is evaluated per point by DirectLight.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/direct_light.h"
#include "radiosity/light_response.h"
#include "radiosity/solver.h"

namespace radiosity {

/// Indirect irradiance at point x of `polygon` (radiosity units) from the solver's
/// current links and radiosities. Thread-safe (reads only). `seed` selects the rays;
/// `rays` (optional) counts those cast.
Rgb finalGatherIndirect(const HierarchicalSolver& solver, int polygon, const Vec3& x,
                        int partialRays = 4, uint64_t seed = 0, uint64_t* rays = nullptr);

/// The final gather's terms at x, for a gather repeated while only the radiosities change
/// (links and subdivision fixed): H_indirect(x) = sum of w times the radiosity that node
/// reflects (B - E for an emitter), over the returned terms. Every source is kept, whatever
/// its radiosity now, so the rays of PARTIAL links are those of a gather in which every
/// source carries light.
struct GatherWeight {
    int node;
    float w;  ///< F(x) V(x), dimensionless (float: 8 bytes a term; a mesh's vertices hold
              ///< hundreds of millions of them)
};
std::vector<GatherWeight> finalGatherWeights(const HierarchicalSolver& solver, int polygon,
                                             const Vec3& x, int partialRays = 4, uint64_t seed = 0,
                                             uint64_t* rays = nullptr);

/// The same gather for every light at once: H[l] = indirect irradiance at x per unit
/// radiance of light l, from `responses` (built on the same solver, same links). H holds
/// responses.lights() values. The rays and V(x) of PARTIAL links are shared by all lights.
void finalGatherResponses(const HierarchicalSolver& solver, const LightResponses& responses,
                          int polygon, const Vec3& x, Rgb* H, int partialRays = 4,
                          uint64_t seed = 0, uint64_t* rays = nullptr);

/// Indirect irradiance at point x of `polygon` gathered by rays (radiosity units): side^2
/// cosine-distributed directions over the hemisphere of its front (stratified, jittered,
/// seeded by `seed`), each bringing the radiosity that the leaf it hits reflects (B - E on
/// an emitter: what it emits is direct light; nothing from a ray that leaves the scene):
///   H_indirect(x) = pi * (1 / N) sum_i L(y_i) = (1 / N) sum_i B_reflected(y_i).
/// Unlike finalGatherIndirect(), every ray reads the radiosity where it lands, at the
/// leaves' resolution: a link from a large source that x partly sees brings the source's
/// mean radiosity there, which in a dim corner next to a block is that of the parts x does
/// not see (bench/RESULTS.md, 2026-11-26: the Cornell box's corners 10-18 % too light). The
/// price is noise, 1 / sqrt(N) of the radiance's spread over the hemisphere, and N rays.
/// `rays` (optional) counts those cast.
Rgb rayGatherIndirect(const HierarchicalSolver& solver, int polygon, const Vec3& x, int side,
                      uint64_t seed, uint64_t* rays = nullptr);
/// The same per light: H[l] = indirect irradiance at x per unit radiance of light l, from
/// `responses` (built on the same solver). H holds responses.lights() values. Leaves added
/// since the responses were solved (responses.covers() false) add nothing.
/// `hits` (optional, side^2 values): the leaf each ray met, -1 where it met none, for a gather
/// of another field along the same rays later (rayGatherField's `hits`).
void rayGatherResponses(const HierarchicalSolver& solver, const LightResponses& responses,
                        int polygon, const Vec3& x, Rgb* H, int side, uint64_t seed,
                        uint64_t* rays = nullptr, int32_t* hits = nullptr);

/// The two gathers of a field other than the solution's: `reflected[s]` stands for what node
/// s reflects (B - E), for every node of the hierarchy (a change of the radiosity, say, which
/// is zero on most nodes). Sources whose field is zero cast no rays for PARTIAL links, so a
/// gather of a local change costs little more than its rays. Linear in the field: a gather
/// of B_now - B_before is the difference of the two gathers, but for where a ray or a
/// PARTIAL link's visibility changed between them.
Rgb finalGatherField(const HierarchicalSolver& solver, std::span<const Rgb> reflected, int polygon,
                     const Vec3& x, int partialRays = 4, uint64_t seed = 0);
Rgb rayGatherField(const HierarchicalSolver& solver, std::span<const Rgb> reflected, int polygon,
                   const Vec3& x, int side, uint64_t seed);
/// The same along rays already cast from x with this side and seed: `hits` holds the leaf each
/// ray met (rayGatherResponses' `hits`, -1: none). A leaf split since is looked up again where
/// its ray meets its plane. Nothing is cast: of what was put in since, only the polygons
/// `faces` (a lamp's, say) are met, by each ray again; anything else neither sends nor blocks.
Rgb rayGatherField(const HierarchicalSolver& solver, std::span<const Rgb> reflected, int polygon,
                   const Vec3& x, int side, uint64_t seed, std::span<const int32_t> hits,
                   std::span<const int> faces = {});

/// Irradiance at point x of `polygon` by final gather (radiosity units):
///   H(x) = sum_l E_l G_l(x) + H_indirect(x),
/// G from `direct` (built on the same solver), H_indirect from finalGatherIndirect().
Rgb gatheredIrradiance(const HierarchicalSolver& solver, const DirectLight& direct, int polygon,
                       const Vec3& x, uint64_t seed = 0);

/// Radiosity at point x of `polygon` by final gather (radiosity units):
///   B(x) = E + rho H(x), H from gatheredIrradiance().
Rgb gatheredRadiosity(const HierarchicalSolver& solver, const DirectLight& direct, int polygon,
                      const Vec3& x, uint64_t seed = 0);

}  // namespace radiosity
