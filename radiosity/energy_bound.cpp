// The energy bound of the clustered solver (solver.h, "Energy bound"): what each leaf
// sees, measured by ray casting; each lamp's links scaled to deliver its power; each
// leaf's gather moved into what it can see.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>
#include <utility>

#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/rng.h"
#include "radiosity/parallel.h"
#include "radiosity/solver.h"
#include "radiosity/tree_walks.h"

namespace radiosity {

void HierarchicalSolver::normaliseLamps(int firstPolygon) {
    // A lamp's face delivers all its power to what it sees: sum_r F_rs V A_r over the links
    // from its elements (one element of the face per receiver region) must be A seen, the
    // face's area times the fraction of its hemisphere that sees a surface (reciprocity,
    // F_rs A_r = F_sr A_s). The links' form factors are integrated on the receivers (2 x 2
    // points), accurate for receivers small against their distance to the lamp only: a
    // wall 5 mm behind a lamp that faces it, as one element, gathered 9 % more than the
    // lamp emits. The links of each emitting face are scaled to deliver exactly its power.
    // Idempotent: a second call finds the sums right.
    const auto& nodes = h_.nodes;
    std::vector<double> delivered(scene_.polygons.size(), 0.0);
    for (const Link& l : links_) {
        const Node& S = nodes[l.source];
        if (reflects(S) || S.polygon < firstPolygon) continue;
        delivered[S.polygon] += l.F * static_cast<double>(l.V) * nodes[l.receiver].area;
    }
    std::vector<int> faces;  // root elements of the emitting faces not yet measured
    for (size_t p = 0; p < delivered.size(); ++p)
        if (delivered[p] > 0 && nodes[h_.polygonRoot[p]].seen < 0)
            faces.push_back(h_.polygonRoot[p]);
    measureSeen(faces, kLampSeenSide, kLampSeenSide);
    links_.forEachMutable([&](Link& l) {
        const Node& S = nodes[l.source];
        if (reflects(S)) return;
        const Node& face = nodes[h_.polygonRoot[S.polygon]];
        if (!(delivered[S.polygon] > 0) || !(face.seen >= 0)) return;
        l.F *= std::min(face.area * face.seen / delivered[S.polygon], kMaxRenormalisation);
    });
}

void HierarchicalSolver::boundGather(size_t firstNode, bool balance, const std::vector<int>* also) {
    const auto& nodes = h_.nodes;
    // Gd: what each leaf gathers from the sources that do not reflect (the lamps), whose
    // links carry exact form factors; light straight from an emitting face feeds nothing
    // back. It is what the leaf sees of the lamps: without the real-shadow correction,
    // which scales those links (above V = 1, too) on purpose (scaleLightLinks).
    const std::vector<Rgb> Gd =
        gatherDown([&](int s) { return Rgb::gray(reflects(nodes[s]) ? 0.0 : 1.0); }, false, true);
    std::vector<int> unmeasured;
    for (size_t n = firstNode; n < nodes.size(); ++n)
        if (!nodes[n].isCluster() && nodes[n].isLeaf() && nodes[n].seen < 0)
            unmeasured.push_back(static_cast<int>(n));
    measureSeenUntilDeadline(unmeasured);
    boundRows(firstNode, Gd, also);
    if (balance && options_.balanceSends) balanceSends(Gd, firstNode, also);
}

double HierarchicalSolver::rowScale(double seen, double seenError, double g, double gd) {
    // G is moved into the interval the rays allow, seen - Gd +- 2 standard errors (and
    // never above 1 - Gd): a G that the measurement cannot tell from the truth is kept,
    // one it says is wrong is corrected. At most kMaxRenormalisation: where the links miss
    // much of what the leaf sees they are not scaled up without end. What reflecting
    // sources fill: what the leaf sees, less the lamps it sees.
    if (!(seen >= 0)) return 1.0;  // not measured (a time budget cut it): no bound
    const double target = seen - gd;
    const double lo = std::max(0.0, target - 2 * seenError);
    const double hi = std::max(lo, std::min(1.0 - gd, target + 2 * seenError));
    return g > 0 ? std::min(std::clamp(g, lo, hi) / g, kMaxRenormalisation) : 1.0;
}

void HierarchicalSolver::boundRows(size_t firstNode, const std::vector<Rgb>& Gd,
                                   const std::vector<int>* also) {
    // G: what each leaf gathers when every source that reflects sends its send scale.
    const auto& nodes = h_.nodes;
    const std::vector<double> send = meanOverLeaves([&](const Node& e) { return e.sendScale; });
    const std::vector<Rgb> G =
        gatherDown([&](int s) { return Rgb::gray(reflects(nodes[s]) ? send[s] : 0.0); }, false);
    boundedLeaves_ = 0;
    maxGather_ = 1;
    for (size_t n = 0; n < nodes.size(); ++n) {
        Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        const double g = G[n].maxComponent();
        maxGather_ = std::max(maxGather_, g);
        if (n >= firstNode ||
            (also && std::binary_search(also->begin(), also->end(), static_cast<int>(n))))
            e.gatherScale = rowScale(e.seen, e.seenError, g, Gd[n].maxComponent());
        if (std::abs(e.gatherScale - 1) > 0.05) ++boundedLeaves_;
    }
}

std::vector<double> HierarchicalSolver::meanOverLeaves(
    const std::function<double(const Node&)>& value) const {
    const auto& nodes = h_.nodes;
    const std::vector<int> pre = preOrder(h_);
    std::vector<int> parent(nodes.size(), -1);
    std::vector<double> x(nodes.size(), 0.0), xa(nodes.size(), 0.0);
    for (int n : pre) {
        const Node& e = nodes[n];
        parent[n] = e.parent;
        if (e.isCluster() || !e.isLeaf()) continue;
        x[n] = value(e) * e.area;
        xa[n] = e.area;
    }
    pullUp(pre, parent, x, xa, /*mean=*/true);
    return x;
}

namespace {

/// The fraction of cosine-distributed rays that meet the front of a surface, from points
/// that `origin(rng, normal)` draws (each about its own normal, which `normal` holds on
/// entry for a planar leaf and is set by `origin` otherwise): first side^2 stratified rays,
/// then more^2 where they disagree. Returns (seen, its standard error). A planar leaf's
/// direction is drawn before its point (the order its measure always had).
template <class Origin>
std::pair<double, double> seenFraction(const Visibility& vis, const Scene& scene, double tMin,
                                       uint64_t seed, int side, int more, int ownPolygon,
                                       const Vec3* planarNormalIn, const Origin& origin) {
    const bool planar = planarNormalIn != nullptr;
    const Vec3 planarNormal = planar ? *planarNormalIn : Vec3{0, 0, 1};
    const HemisphereFrame planarFrame(planarNormal);
    Rng rng(0xC0FFEEull ^ (seed * 0x9E3779B97F4A7C15ull));
    int hits = 0, cast = 0;
    const auto castRays = [&](int k) {
        for (int cell = 0; cell < k * k; ++cell) {
            Vec3 normal = planarNormal, dir, org;
            if (planar) {
                dir = cosineDirection(planarFrame, cell, k, rng);
                org = origin(rng, normal);
            } else {
                org = origin(rng, normal);
                dir = cosineDirection(HemisphereFrame(normal), cell, k, rng);
            }
            // A front, reflecting or a lamp (a thin part's back face hides its twin's front).
            const FrontHit found = intersectFront(vis, scene, org, dir, tMin);
            if (found.front && found.hit.polygon != ownPolygon) ++hits;
        }
        cast += k * k;
    };
    castRays(side);
    if (more > side && hits > 0 && hits < cast) {  // partly open: a finer estimate
        hits = cast = 0;
        castRays(more);
    }
    const double seen = static_cast<double>(hits) / cast;
    return {seen, std::sqrt(seen * (1 - seen) / cast)};
}

}  // namespace

void HierarchicalSolver::measureSeen(const std::vector<int>& leaves, int side, int more) {
    // Cosine-distributed rays, stratified over the hemisphere (detail/hemisphere.h), from
    // a random point of the leaf each.
    const double diag = glm::length(h_.nodes[Hierarchy::kRoot].bounds.diagonal());
    const double tMin = 1e-6 * diag;  // above Embree's float rounding (visibility.h)
    parallelFor(leaves.size(), 16, [&](size_t i) {
        Node& e = h_.nodes[leaves[i]];
        const auto origin = [&e](Rng& rng, Vec3& normal) {
            normal = e.normal;
            return pointOnElement(e, rng.uniform(), rng.uniform());
        };
        std::tie(e.seen, e.seenError) =
            seenFraction(*vis_, scene_, tMin, static_cast<uint64_t>(leaves[i]), side, more,
                         e.polygon, &e.normal, origin);
    });
}

void HierarchicalSolver::measureSeenByPatch(const std::vector<int>& leaves) {
    // A polygon's root element that is a leaf, in a face cluster of several polygons, takes
    // the `seen` of its face cluster, measured once from points spread over the cluster by
    // area: on a reconstructed surface of thousands of small triangles, 64 to 256 rays per
    // triangle were most of the solve (the staircase hall: 50 of 59 s of its first round),
    // and neighbouring triangles of one nearly planar surface see the same room. Other leaves
    // (a polygon of its own, an element the refinement split) are measured one by one.
    std::vector<int> single;
    std::vector<std::pair<int, int>> byPatch;  // (face cluster node, leaf)
    for (int l : leaves) {
        const Node& e = h_.nodes[l];
        const int patch = e.polygon >= 0 ? h_.polygonPatch[e.polygon] : -1;
        if (patch >= 0 && h_.polygonRoot[e.polygon] == l &&
            h_.nodes[patch].polyEnd - h_.nodes[patch].polyBegin >= kSeenPatchPolygons)
            byPatch.emplace_back(patch, l);
        else
            single.push_back(l);
    }
    measureSeen(single);
    std::sort(byPatch.begin(), byPatch.end());
    std::vector<size_t> start;  // runs of one patch in byPatch
    for (size_t i = 0; i < byPatch.size(); ++i)
        if (i == 0 || byPatch[i].first != byPatch[i - 1].first) start.push_back(i);
    start.push_back(byPatch.size());
    const double diag = glm::length(h_.nodes[Hierarchy::kRoot].bounds.diagonal());
    const double tMin = 1e-6 * diag;
    parallelFor(start.size() - 1, 4, [&](size_t r) {
        const int patch = byPatch[start[r]].first;
        const auto origin = [&](Rng& rng, Vec3& normal) {
            const double u = rng.uniform(), v = rng.uniform(), w = rng.uniform();
            return h_.samplePoint(patch, u, v, w, &normal);
        };
        const auto [seen, error] = seenFraction(*vis_, scene_, tMin, static_cast<uint64_t>(patch),
                                                8, 16, -1, nullptr, origin);
        for (size_t i = start[r]; i < start[r + 1]; ++i) {
            h_.nodes[byPatch[i].second].seen = seen;
            h_.nodes[byPatch[i].second].seenError = error;
        }
    });
}

}  // namespace radiosity
