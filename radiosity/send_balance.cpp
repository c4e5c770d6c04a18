// The balance of rows and columns of the energy bound (solver.h, "Balance of what leaves
// send"): scalar passes over the links, on compact copies of the topology and of the
// leaves' values (a Node is 750 bytes; streaming the node array once per pass cost more
// than the passes). Each pass is a gather (rows: what every leaf gathers from the
// sources' send scales) or its adjoint (columns: what every leaf hands out to the
// receivers' gather scales), with the solver's own rules: a leaf gathers through its own
// links and its ancestors', and a cluster receiver hands a link's light to each surface
// by the surface's orientation (directional_irradiance.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "radiosity/detail/seen_interval.h"
#include "radiosity/parallel.h"
#include "radiosity/solver.h"
#include "radiosity/tree_walks.h"

namespace radiosity {

namespace {

using Bins = std::array<double, 6>;

/// Bin 2a (+e_a) or 2a + 1 (-e_a) of the direction bins for component v_a.
template <class V>
inline int bin(const V& v, int a) {
    return 2 * a + (v[a] < 0 ? 1 : 0);
}

/// The links from sources that reflect, as the balance reads them.
struct BalanceLinks {
    std::vector<int> receiver, source;
    std::vector<double> FV;
    std::vector<Vec3> w;             ///< arrival direction in a cluster receiver's frame
    std::vector<int> receiverStart;  ///< runs of one receiver: [start[i], start[i + 1])
    std::vector<int> bySource;       ///< link indices grouped by source, in runs
    std::vector<int> sourceStart;    ///< [start[s], start[s + 1]) (every node s)
};

/// The hierarchy as the balance reads it: every node after its parent (pre-order), and
/// per node its parent, area, kind and centre; the clusters that receive light from a
/// reflecting source (their slots and frames), the polygons' root elements with their
/// cluster ancestors and their normals in those frames, and the leaves.
struct BalanceTopology {
    std::vector<int> pre, parent;
    std::vector<double> area;
    std::vector<char> cluster, reflecting;
    std::vector<Vec3> centre;
    std::vector<int> clusters, roots, slot;
    std::vector<std::array<Vec3, 3>> frame;
    std::vector<int> ancestorStart, ancestor;  ///< root i: ancestor[start[i], start[i + 1])
    std::vector<glm::vec3> ancestorNormal;     ///< float: 3.3 M of them at 215 k polygons
    std::vector<int> leaves;
};

BalanceTopology readTopology(const Hierarchy& h, const std::vector<Link>& links) {
    const auto& nodes = h.nodes;
    const size_t N = nodes.size();
    BalanceTopology t;
    t.pre = preOrder(h);
    t.parent.assign(N, -1);
    t.area.resize(N);
    t.cluster.resize(N);
    t.reflecting.resize(N);
    t.centre.resize(N);
    for (int n : t.pre) {
        const Node& node = nodes[n];
        t.parent[n] = node.parent;
        t.area[n] = node.area;
        t.cluster[n] = node.isCluster();
        t.reflecting[n] = reflects(node);
        t.centre[n] = node.centre;
    }
    t.slot.assign(N, -1);
    for (const Link& l : links)
        if (t.cluster[l.receiver] && t.reflecting[l.source] && t.slot[l.receiver] < 0) {
            t.slot[l.receiver] = static_cast<int>(t.clusters.size());
            t.clusters.push_back(l.receiver);
        }
    {
        std::vector<int> all;
        h.clustersAndRoots(all, t.roots);
    }
    t.frame.resize(t.clusters.size());
    for (size_t i = 0; i < t.clusters.size(); ++i) t.frame[i] = h.frame(nodes[t.clusters[i]]);
    t.ancestorStart.reserve(t.roots.size() + 1);
    t.ancestorStart.push_back(0);
    {
        size_t count = 0;
        for (int e : t.roots)
            for (int a = t.parent[e]; a >= 0; a = t.parent[a]) count += t.slot[a] >= 0;
        t.ancestor.reserve(count);
        t.ancestorNormal.reserve(count);
    }
    for (int e : t.roots) {
        const Vec3 n = nodes[e].normal;
        for (int a = t.parent[e]; a >= 0; a = t.parent[a]) {
            if (t.slot[a] < 0) continue;  // gathers nothing
            const auto& f = t.frame[t.slot[a]];
            t.ancestor.push_back(t.slot[a]);
            t.ancestorNormal.push_back(
                glm::vec3(Vec3{glm::dot(f[0], n), glm::dot(f[1], n), glm::dot(f[2], n)}));
        }
        t.ancestorStart.push_back(static_cast<int>(t.ancestor.size()));
    }
    for (int n : t.pre)
        if (!t.cluster[n] && nodes[n].isLeaf()) t.leaves.push_back(n);
    return t;
}

/// The links from reflecting sources, in the solver's receiver order, and an index by
/// source (counting sort: deterministic).
BalanceLinks readLinks(const std::vector<Link>& links, const BalanceTopology& t) {
    const size_t N = t.parent.size();
    BalanceLinks L;
    for (auto* v : {&L.receiver, &L.source}) v->reserve(links.size());
    L.FV.reserve(links.size());
    L.w.reserve(links.size());
    for (const Link& l : links) {
        if (!t.reflecting[l.source]) continue;
        if (L.receiver.empty() || L.receiver.back() != l.receiver)
            L.receiverStart.push_back(static_cast<int>(L.receiver.size()));
        L.receiver.push_back(l.receiver);
        L.source.push_back(l.source);
        L.FV.push_back(l.F * static_cast<double>(l.V));
        Vec3 w{0, 0, 0};
        if (t.cluster[l.receiver]) {  // linkDirection(R, S) in R's frame
            const Vec3 d = t.centre[l.source] - t.centre[l.receiver];
            const double len = glm::length(d);
            const auto& f = t.frame[t.slot[l.receiver]];
            if (len > 0) w = Vec3{glm::dot(f[0], d), glm::dot(f[1], d), glm::dot(f[2], d)} / len;
        }
        L.w.push_back(w);
    }
    const int M = static_cast<int>(L.receiver.size());
    L.receiverStart.push_back(M);
    L.sourceStart.assign(N + 1, 0);
    for (int k = 0; k < M; ++k) ++L.sourceStart[L.source[k] + 1];
    for (size_t n = 0; n < N; ++n) L.sourceStart[n + 1] += L.sourceStart[n];
    std::vector<int> next(L.sourceStart.begin(), L.sourceStart.end() - 1);
    L.bySource.resize(M);
    for (int k = 0; k < M; ++k) L.bySource[next[L.source[k]]++] = k;
    return L;
}

/// Per leaf (in BalanceTopology::leaves order): its two scales, what it sees (+- its
/// standard error), what it gathers from the lamps, and whether the balance sets it.
struct LeafScales {
    std::vector<double> gather, send, seen, seenError, gd;
    std::vector<char> moves;
};

/// The two passes of the balance over compact copies, with their scratch arrays.
class BalancePasses {
  public:
    BalancePasses(const BalanceTopology& t, const BalanceLinks& L)
        : t_(t),
          L_(L),
          x_(t.parent.size()),
          xa_(t.parent.size()),
          P_(t.parent.size()),
          C_(t.parent.size()),
          bins_(t.clusters.size()) {}

    /// Columns: each reflecting leaf's send scale moved into what it sees (+- 2 standard
    /// errors), given what it hands out to the receivers' gather scales; then the sends
    /// held at a geometric mean of 1 by area (`gauge`). Returns whether the sends settled
    /// (area-weighted mean relative change below `tolerance`).
    bool columns(LeafScales& s, bool gauge, double maxScale, double tolerance) {
        const auto& leaves = t_.leaves;
        const size_t K = leaves.size();
        // W: the receivers' leaf areas weighted by their gather scales (x), and per
        // receiving cluster by direction bin, its polygons' W by their normals.
        std::vector<double> Ar(K);
        for (size_t i = 0; i < K; ++i) Ar[i] = t_.area[leaves[i]] * s.gather[i];
        pull(Ar, /*mean=*/false);
        std::fill(bins_.begin(), bins_.end(), Bins{});
        for (size_t i = 0; i < t_.roots.size(); ++i)
            for (int k = t_.ancestorStart[i]; k < t_.ancestorStart[i + 1]; ++k)
                for (int a = 0; a < 3; ++a)
                    bins_[t_.ancestor[k]][bin(t_.ancestorNormal[k], a)] +=
                        x_[t_.roots[i]] * static_cast<double>(std::abs(t_.ancestorNormal[k][a]));
        // P_s: what the links from s deliver per unit of what s sends (m^2).
        parallelFor(P_.size(), 1024, [&](size_t src) {
            double p = 0;
            for (int j = L_.sourceStart[src]; j < L_.sourceStart[src + 1]; ++j) {
                const int k = L_.bySource[j], rc = L_.receiver[k];
                double w = 0;
                if (t_.cluster[rc]) {
                    const Bins& b = bins_[t_.slot[rc]];
                    for (int a = 0; a < 3; ++a) w += std::abs(L_.w[k][a]) * b[bin(L_.w[k], a)];
                } else {
                    w = x_[rc];
                }
                p += L_.FV[k] * w;
            }
            P_[src] = p;
        });
        // C_m: P / A summed down from the root.
        for (int n : t_.pre)
            C_[n] = (t_.parent[n] >= 0 ? C_[t_.parent[n]] : 0.0) +
                    (t_.area[n] > 0 ? P_[n] / t_.area[n] : 0.0);  // guard: a zero-area node
        // Each send moved into what the leaf sees (+- 2 standard errors), then the sends
        // held at a geometric mean of 1 by area: rows and columns fix only the products
        // of gather and send scales, a common factor moves freely between them.
        const std::vector<double> before = s.send;
        double logSum = 0, areaSum = 0;
        for (size_t i = 0; i < K; ++i) {
            if (!s.moves[i] || !t_.reflecting[leaves[i]] || !(s.seen[i] >= 0)) continue;
            const double c = C_[leaves[i]] * s.send[i];
            if (c > 0) s.send[i] *= SeenInterval(s.seen[i], s.seenError[i], 1.0).clamp(c) / c;
            if (!(s.send[i] > 0)) continue;  // sees nothing: out of the mean (clamped below)
            logSum += t_.area[leaves[i]] * std::log(s.send[i]);
            areaSum += t_.area[leaves[i]];
        }
        // (A partial balance, of an inserted object's leaves against the fixed rest of
        // the scene, has no free factor: no gauge.)
        const double g = areaSum > 0 && gauge ? std::exp(-logSum / areaSum) : 1.0;
        double change = 0, changeArea = 0;  // area-weighted mean relative change
        for (size_t i = 0; i < K; ++i) {
            if (!s.moves[i] || !t_.reflecting[leaves[i]]) continue;
            s.send[i] = std::clamp(s.send[i] * g, 1 / maxScale, maxScale);
            change += t_.area[leaves[i]] * std::abs(s.send[i] / before[i] - 1);
            changeArea += t_.area[leaves[i]];
        }
        return !(changeArea > 0) || change < tolerance * changeArea;
    }

    /// Rows: what each node gathers (by node id) when every source sends the area mean of
    /// its leaves' send scales, through its own links and, for an element, its ancestors'.
    const std::vector<double>& gathered(const std::vector<double>& send) {
        pull(send, /*mean=*/true);
        const std::vector<double> sourceSend = x_;
        std::fill(x_.begin(), x_.end(), 0.0);
        std::fill(bins_.begin(), bins_.end(), Bins{});
        parallelFor(L_.receiverStart.size() - 1, 64, [&](size_t i) {
            for (int k = L_.receiverStart[i]; k < L_.receiverStart[i + 1]; ++k) {
                const int rc = L_.receiver[k];
                const double v = L_.FV[k] * sourceSend[L_.source[k]];
                if (!t_.cluster[rc]) {
                    x_[rc] += v;
                    continue;
                }
                for (int a = 0; a < 3; ++a)
                    bins_[t_.slot[rc]][bin(L_.w[k], a)] += v * std::abs(L_.w[k][a]);
            }
        });
        // Down: a root element takes what its cluster ancestors gathered, by its normal;
        // every element what its element ancestors gathered.
        parallelFor(t_.roots.size(), 256, [&](size_t i) {
            for (int k = t_.ancestorStart[i]; k < t_.ancestorStart[i + 1]; ++k)
                for (int a = 0; a < 3; ++a)
                    x_[t_.roots[i]] += bins_[t_.ancestor[k]][bin(t_.ancestorNormal[k], a)] *
                                       static_cast<double>(std::abs(t_.ancestorNormal[k][a]));
        });
        for (int n : t_.pre)
            if (!t_.cluster[n] && t_.parent[n] >= 0 && !t_.cluster[t_.parent[n]])
                x_[n] += x_[t_.parent[n]];
        return x_;
    }

  private:
    /// Sums (weight 1) or area means of per-leaf values over every node (tree_walks.h),
    /// into x_.
    void pull(const std::vector<double>& leafValue, bool mean) {
        std::fill(x_.begin(), x_.end(), 0.0);
        std::fill(xa_.begin(), xa_.end(), 0.0);
        for (size_t i = 0; i < t_.leaves.size(); ++i) {
            const int n = t_.leaves[i];
            x_[n] = mean ? leafValue[i] * t_.area[n] : leafValue[i];
            xa_[n] = t_.area[n];
        }
        pullUp(t_.pre, t_.parent, x_, xa_, mean);
    }

    const BalanceTopology& t_;
    const BalanceLinks& L_;
    std::vector<double> x_, xa_, P_, C_;
    std::vector<Bins> bins_;
};

}  // namespace

void HierarchicalSolver::balanceSends(const std::vector<Rgb>& Gd, size_t firstNode,
                                      const std::vector<int>* also) {
    const BalanceTopology t = readTopology(h_, links_.byReceiver());
    const BalanceLinks L = readLinks(links_.byReceiver(), t);
    const std::vector<int>& leaves = t.leaves;
    const size_t K = leaves.size();
    LeafScales s;
    for (auto* v : {&s.gather, &s.send, &s.seen, &s.seenError, &s.gd}) v->resize(K);
    s.moves.resize(K);
    for (size_t i = 0; i < K; ++i) {
        s.moves[i] = static_cast<size_t>(leaves[i]) >= firstNode ||
                     (also && std::binary_search(also->begin(), also->end(), leaves[i]));
        const Node& e = h_.nodes[leaves[i]];
        s.gather[i] = e.gatherScale;
        s.send[i] = e.sendScale;
        s.seen[i] = e.seen;
        s.seenError[i] = e.seenError;
        s.gd[i] = Gd[leaves[i]].maxComponent();
    }
    BalancePasses passes(t, L);
    bool settled = false;
    for (int it = 0; it < kBalanceIterations && !settled; ++it) {
        settled =
            passes.columns(s, /*gauge=*/firstNode == 0, kMaxRenormalisation, kBalanceTolerance);
        // The rows come last, so that the contraction bound holds whatever the columns
        // reached (solver.h, "Balance of what leaves send").
        const std::vector<double>& G = passes.gathered(s.send);
        const std::vector<double> group =
            groupRowScales([&](int n) { return G[static_cast<size_t>(n)]; },
                           [&](int n) { return Gd[static_cast<size_t>(n)].maxComponent(); });
        boundedLeaves_ = 0;
        maxGather_ = 1;
        for (size_t i = 0; i < K; ++i) {
            if (s.moves[i])
                s.gather[i] = rowScale(s.seen[i], s.seenError[i], G[leaves[i]], s.gd[i],
                                       group[static_cast<size_t>(leaves[i])]);
            maxGather_ = std::max(maxGather_, G[leaves[i]]);
            if (std::abs(s.gather[i] - 1) > 0.05) ++boundedLeaves_;
        }
    }
    for (size_t i = 0; i < K; ++i) {
        Node& e = h_.nodes[leaves[i]];
        e.gatherScale = s.gather[i];
        e.sendScale = s.send[i];
    }
}

}  // namespace radiosity
