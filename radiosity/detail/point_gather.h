// The final gather's traversal at one point (radiosity/final_gather.h), shared by the
// gather of single points and the gather of many points with their far field shared per
// receiving element (radiosity/shared_gather.h).
#pragma once

#include <algorithm>
#include <cstdint>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/rng.h"
#include "radiosity/detail/transfer.h"
#include "radiosity/solver.h"

namespace radiosity::detail {

/// Fraction of `count` rays from x to stratified points of node s that arrive.
inline double pointVisibility(const HierarchicalSolver& solver, int polygon, const Vec3& x,
                              const Vec3& n, int s, int count, Rng& rng, uint64_t& rays) {
    const Hierarchy& h = solver.hierarchy();
    const int k = strataSide(count);
    int perm[64];
    shuffledStrata(rng, k, perm);
    Vec3 from[64], to[64];
    int m = 0;
    for (int i = 0; i < count; ++i) {
        const int cell = perm[i];
        const double u = ((cell % k) + rng.uniform()) / k, v = ((cell / k) + rng.uniform()) / k;
        Vec3 ns;
        const Vec3 y = h.samplePoint(s, u, v, rng.uniform(), &ns);
        // Only mutually facing pairs carry light between one-sided surfaces.
        if (!(glm::dot(y - x, n) > 0) || !(glm::dot(x - y, ns) > 0)) continue;
        from[m] = x;
        to[m] = y;
        ++m;
    }
    if (m == 0) return 0.0;
    const int polyS = h.nodes[s].isCluster() ? -1 : h.nodes[s].polygon;
    const int visible = solver.visibility().visibleBatch(from, to, m, nullptr, polygon, polyS);
    rays += static_cast<uint64_t>(m);
    return static_cast<double>(visible) / m;
}

/// What an element source sends to x: B_s F(x), where F = F(x -> s) is given. Where x is
/// close to s (F above kDescendF) the source's own subdivision is used instead: the sum
/// over its children of B_c F(x -> c). A link is accepted for the receiver element as a
/// whole (its mean F is small), yet a point of it near the source's edge can see the
/// source at a large angle, and there the source's mean B is wrong: a wall that is bright
/// near a corner and dark elsewhere would light the corner with its mean.
constexpr double kDescendF = 0.05;

template <class Accumulate>
void elementWeights(const Hierarchy& h, const Vec3& x, const Vec3& n, int s, double F, double V,
                    Accumulate& acc) {
    const Node& S = h.nodes[s];
    if (S.isLeaf() || !(F > kDescendF)) {
        acc(s, F * V);
        return;
    }
    for (int k = 0; k < S.childCount; ++k) {
        const Node& C = h.nodes[S.firstChild + k];
        const double Fc = pointToPolygon(x, n, C.v.data(), C.vertexCount, C.normal);
        if (Fc > 0) elementWeights(h, x, n, S.firstChild + k, Fc, V, acc);
    }
}

/// Smallest F(x) for which a PARTIAL link's visibility is measured from x. Below it the
/// link's own V (its mean over the receiving element) is kept: the term can then move the
/// gather by less than kPointVisibilityF times the source's radiosity, and a finely cut
/// rough wall has hundreds of such links per point, whose rays made nine tenths of its
/// vertex lighting's time.
constexpr double kPointVisibilityF = 1e-3;

/// One link's terms at x: acc(node, w) with w = F(x) V(x) for the link r <- s that gathers
/// into an element or cluster above x (F per point; an element source descends into its
/// children near x; V measured from x on a PARTIAL link).
template <class Accumulate>
void gatherLink(const HierarchicalSolver& solver, int polygon, const Vec3& x, const Vec3& n,
                const Link& l, int partialRays, Rng& rng, uint64_t& cast, Accumulate& acc) {
    const Hierarchy& h = solver.hierarchy();
    const Node& S = h.nodes[l.source];
    double F;
    if (!S.isCluster()) {
        F = pointToPolygon(x, n, S.v.data(), S.vertexCount, S.normal);
    } else {
        F = pointToNode(h, x, n, S);  // the link's own bounded estimate, from x
    }
    if (!(F > 0)) return;
    const double V = l.type == VisibilityType::partial && partialRays > 0 && F > kPointVisibilityF
                         ? pointVisibility(solver, polygon, x, n, l.source, partialRays, rng, cast)
                         : static_cast<double>(l.V);
    if (!(V > 0)) return;
    if (S.isCluster())
        acc(l.source, F * V);
    else
        elementWeights(h, x, n, l.source, F, V, acc);
}

/// The random numbers of the gather at a point of seed `seed`.
inline Rng gatherRng(uint64_t seed) {
    return Rng(seed * 0xD1B54A32D192ED03ull + 0x51ED27ull);
}

/// Whether a link can carry light at all (a PARTIAL link of V 0 may still, seen from x).
inline bool mayCarry(const Link& l) {
    return l.V > 0 || l.type == VisibilityType::partial;
}

/// The final gather's traversal: for every link on the chain above the leaf holding x
/// whose source `carries(source)` and that `take(receiver, link)` keeps, calls acc(node, w)
/// with the weight w = F(x) V(x) by which the radiosity that `node` reflects reaches x.
template <class Take, class Carries, class Accumulate>
void gatherWeights(const HierarchicalSolver& solver, int polygon, const Vec3& x, int partialRays,
                   uint64_t seed, uint64_t* rays, const Take& take, const Carries& carries,
                   Accumulate& acc) {
    const Hierarchy& h = solver.hierarchy();
    const Vec3& n = solver.scene().polygons[polygon].normal;
    partialRays = std::clamp(partialRays, 0, 64);
    Rng rng = gatherRng(seed);
    uint64_t cast = 0;
    for (int node = h.locateLeaf(polygon, x); node >= 0; node = h.nodes[node].parent) {
        for (const Link& l : solver.linksOf(node)) {
            if (!mayCarry(l) || !take(node, l) || !carries(l.source)) continue;
            gatherLink(solver, polygon, x, n, l, partialRays, rng, cast, acc);
        }
    }
    if (rays) *rays += cast;
}

template <class Carries, class Accumulate>
void gatherWeights(const HierarchicalSolver& solver, int polygon, const Vec3& x, int partialRays,
                   uint64_t seed, uint64_t* rays, const Carries& carries, Accumulate& acc) {
    auto all = [](int, const Link&) { return true; };
    gatherWeights(solver, polygon, x, partialRays, seed, rays, all, carries, acc);
}

}  // namespace radiosity::detail
