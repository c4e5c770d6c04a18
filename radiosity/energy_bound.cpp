// The energy bound of the clustered solver (solver.h, "Energy bound"): what each leaf
// sees, measured by ray casting; each lamp's links scaled to deliver its power; each
// leaf's gather moved into what it can see.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <span>
#include <tuple>
#include <utility>

#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/rng.h"
#include "radiosity/detail/seen_interval.h"
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

double HierarchicalSolver::rowScale(double seen, double seenError, double g, double gd,
                                    double group) {
    // G is moved into the interval the rays allow, seen - Gd +- 2 standard errors (and
    // never above 1 - Gd): a G that the measurement cannot tell from the truth is kept,
    // one it says is wrong is corrected. At most kMaxRenormalisation: where the links miss
    // much of what the leaf sees they are not scaled up without end. What reflecting
    // sources fill: what the leaf sees, less the lamps it sees. `group` is the correction
    // its ancestors' surfaces found (groupRowScales), applied first.
    if (!(seen >= 0)) return 1.0;  // not measured (a time budget cut it): no bound
    const SeenInterval allowed(seen - gd, seenError, 1.0 - gd);
    const double gc = g * group;
    return gc > 0 ? std::min(allowed.clamp(gc) / g, kMaxRenormalisation) : 1.0;
}

namespace {

/// A measured leaf below an element: its area, G, the target of G (seen - Gd, within
/// [0, 1 - Gd]) and the interval its own rays allow, and its measurement's variance times
/// the area squared.
struct RowLeaf {
    double A, g, target;
    SeenInterval allowed;
    double var;
};

/// An element of a polygon's tree in pre-order: its node, the entry of its parent (-1 at
/// the polygon's root) and the range of its measured leaves in the polygon's RowLeaf list.
struct RowElement {
    int node, parent;
    size_t begin, end;
};

/// The polygon tree below node n in one depth-first pass: the measured leaves, with their G
/// (g) and the interval their rays allow (seen - gd +- 2 standard errors, as rowScale),
/// appended to `leaves`, and every element with the range of its leaves to `elements`.
void collectRowLeaves(const std::vector<Node>& nodes, int n, int parent,
                      const std::function<double(int)>& g, const std::function<double(int)>& gd,
                      std::vector<RowLeaf>& leaves, std::vector<RowElement>& elements) {
    const Node& e = nodes[n];
    const size_t first = leaves.size(), entry = elements.size();
    elements.push_back({n, parent, first, first});
    if (e.isLeaf()) {
        const double gn = g(n), target = e.seen - gd(n);
        if (!(e.seen >= 0) || !(gn > 0)) return;
        const SeenInterval allowed(target, e.seenError, 1.0 - gd(n));
        leaves.push_back({e.area, gn, allowed.clamp(target), allowed,
                          e.area * e.area * e.seenError * e.seenError});
        elements[entry].end = leaves.size();
        return;
    }
    const Node& c0 = nodes[e.firstChild];
    bool shared = true;  // every child a leaf holding the same measurement
    for (int k = 0; k < e.childCount; ++k) {
        const Node& c = nodes[e.firstChild + k];
        shared = shared && c.isLeaf() && c.seen == c0.seen && c.seenError == c0.seenError;
        collectRowLeaves(nodes, e.firstChild + k, static_cast<int>(entry), g, gd, leaves, elements);
    }
    elements[entry].end = leaves.size();
    // Children that took their parent's `seen` (a leaf split for a new shadow,
    // dynamic_objects.cpp) share one measurement: its error counts once, for their whole
    // area, not as independent ones.
    if (shared && leaves.size() > first + 1) {
        double A = 0;
        for (size_t i = first; i < leaves.size(); ++i) {
            A += leaves[i].A;
            leaves[i].var = 0;
        }
        leaves[first].var = A * A * c0.seenError * c0.seenError;
    }
}

/// The factor on the G of `leaves`, starting from c (their ancestors'), that brings the
/// area mean of those whose own rays cannot tell their G from their target into the
/// interval of those targets' mean (2 standard errors of it). A leaf outside its own
/// interval is decided by its own rays (a leaf half under a wall gathers twice what it
/// sees) and is not evidence of what the surface shares; a leaf that the factor brings into
/// its interval is, so the set and the factor are found together (a few rounds).
double groupFactor(std::span<const RowLeaf> leaves, double c, double maxScale) {
    for (int round = 0; round < 4; ++round) {
        double A = 0, sumG = 0, sumTarget = 0, var = 0;
        int count = 0;
        for (const RowLeaf& l : leaves) {
            if (!l.allowed.holds(c * l.g)) continue;
            A += l.A;
            sumG += l.A * c * l.g;
            sumTarget += l.A * l.target;
            var += l.var;
            ++count;
        }
        if (count < 2 || !(sumG > 0)) return c;
        const double mean = sumG / A, target = sumTarget / A, err = std::sqrt(var) / A;
        const double next =
            std::clamp(c * std::clamp(mean, target - 2 * err, target + 2 * err) / mean,
                       1 / maxScale, maxScale);
        if (next == c) return c;
        c = next;
    }
    return c;
}

}  // namespace

std::vector<double> HierarchicalSolver::groupRowScales(const std::function<double(int)>& g,
                                                       const std::function<double(int)>& gd) const {
    // A leaf's `seen` is measured with a standard error of 2-3 % (64-256 rays), so the row
    // bound keeps any G within 2 of them: a G a few per cent short on every leaf of a
    // surface is kept, though the surface as a whole says it is short. That is how the
    // coarse links' shared shortfall (the Cornell box's ceiling 4 % dark at epsilon 1e-4
    // against the full-matrix reference, bench/surface_levels) stayed. The leaves of one
    // element are measured independently, so their area mean has a far smaller error: from
    // each polygon's root element down, an element's leaves are moved together by the factor
    // that brings their area mean into the interval of their targets' mean, each leaf then
    // into its own (rowScale). Returns that factor per node (1 where nothing was moved).
    // The leaves of each polygon are collected once; each element's group is its range of
    // them. Which leaves count depends on the factor its ancestors found, so the means are
    // taken again per element: O(leaves x depth) additions, no allocation per element.
    const auto& nodes = h_.nodes;
    std::vector<double> factor(nodes.size(), 1.0);
    parallelFor(h_.polygonRoot.size(), 256, [&](size_t p) {
        const int root = h_.polygonRoot[p];
        if (root < 0 || nodes[root].isLeaf()) return;
        std::vector<RowLeaf> leaves;
        std::vector<RowElement> elements;
        collectRowLeaves(nodes, root, -1, g, gd, leaves, elements);
        std::vector<double> below(elements.size());     // the factor an element passes down
        for (size_t i = 0; i < elements.size(); ++i) {  // pre-order: parents first
            const RowElement& el = elements[i];
            const double c = el.parent >= 0 ? below[static_cast<size_t>(el.parent)] : 1.0;
            factor[static_cast<size_t>(el.node)] = c;
            below[i] = nodes[el.node].isLeaf()
                           ? c
                           : groupFactor(std::span<const RowLeaf>(leaves).subspan(
                                             el.begin, el.end - el.begin),
                                         c, kMaxRenormalisation);
        }
    });
    return factor;
}

void HierarchicalSolver::boundRows(size_t firstNode, const std::vector<Rgb>& Gd,
                                   const std::vector<int>* also) {
    // G: what each leaf gathers when every source that reflects sends its send scale.
    const auto& nodes = h_.nodes;
    const std::vector<double> send = meanOverLeaves([&](const Node& e) { return e.sendScale; });
    const std::vector<Rgb> G =
        gatherDown([&](int s) { return Rgb::gray(reflects(nodes[s]) ? send[s] : 0.0); }, false);
    const std::vector<double> group =
        groupRowScales([&](int n) { return G[static_cast<size_t>(n)].maxComponent(); },
                       [&](int n) { return Gd[static_cast<size_t>(n)].maxComponent(); });
    boundedLeaves_ = 0;
    maxGather_ = 1;
    for (size_t n = 0; n < nodes.size(); ++n) {
        Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        const double g = G[n].maxComponent();
        maxGather_ = std::max(maxGather_, g);
        if (n >= firstNode ||
            (also && std::binary_search(also->begin(), also->end(), static_cast<int>(n))))
            e.gatherScale = rowScale(e.seen, e.seenError, g, Gd[n].maxComponent(), group[n]);
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
