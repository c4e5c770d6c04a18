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

}  // namespace

void HierarchicalSolver::balanceSends(const std::vector<Rgb>& Gd, size_t firstNode,
                                      const std::vector<int>* also) {
    const auto& nodes = h_.nodes;
    const size_t N = nodes.size();

    // Topology: every node after its parent (pre-order), parents, areas; the clusters and
    // the polygons' root elements.
    const std::vector<int> pre = preOrder(h_);
    std::vector<int> parent(N, -1);
    std::vector<double> area(N);
    std::vector<char> cluster(N), reflecting(N);
    std::vector<Vec3> centre(N);
    for (int n : pre) {
        const Node& node = nodes[n];
        parent[n] = node.parent;
        area[n] = node.area;
        cluster[n] = node.isCluster();
        reflecting[n] = reflects(node);
        centre[n] = node.centre;
    }
    // The clusters that receive light from a reflecting source (their slots), and the
    // polygons' root elements.
    std::vector<int> clusters, roots, slot(N, -1);
    for (const Link& l : links_)
        if (cluster[l.receiver] && reflecting[l.source] && slot[l.receiver] < 0) {
            slot[l.receiver] = static_cast<int>(clusters.size());
            clusters.push_back(l.receiver);
        }
    {
        std::vector<int> all;
        h_.clustersAndRoots(all, roots);
    }
    std::vector<std::array<Vec3, 3>> frame(clusters.size());
    for (size_t i = 0; i < clusters.size(); ++i) frame[i] = nodes[clusters[i]].frame;
    // Each root element's cluster ancestors, and its normal in their frames.
    std::vector<int> ancestorStart{0}, ancestor;
    std::vector<glm::vec3> ancestorNormal;  // float: 3.3 M of them at 215 k polygons
    ancestorStart.reserve(roots.size() + 1);
    {
        size_t count = 0;
        for (int e : roots)
            for (int a = parent[e]; a >= 0; a = parent[a]) count += slot[a] >= 0;
        ancestor.reserve(count);
        ancestorNormal.reserve(count);
    }
    for (int e : roots) {
        const Vec3 n = nodes[e].normal;
        for (int a = parent[e]; a >= 0; a = parent[a]) {
            if (slot[a] < 0) continue;  // gathers nothing
            const auto& f = frame[slot[a]];
            ancestor.push_back(slot[a]);
            ancestorNormal.push_back(
                glm::vec3(Vec3{glm::dot(f[0], n), glm::dot(f[1], n), glm::dot(f[2], n)}));
        }
        ancestorStart.push_back(static_cast<int>(ancestor.size()));
    }
    // The leaves' values.
    std::vector<int> leaves;
    for (int n : pre)
        if (!cluster[n] && nodes[n].isLeaf()) leaves.push_back(n);
    const size_t K = leaves.size();
    std::vector<double> gather(K), send(K), seen(K), seenError(K), gd(K);
    std::vector<char> moves(K);  // the leaves whose scales the balance sets
    for (size_t i = 0; i < K; ++i) {
        moves[i] = static_cast<size_t>(leaves[i]) >= firstNode ||
                   (also && std::binary_search(also->begin(), also->end(), leaves[i]));
        const Node& e = nodes[leaves[i]];
        gather[i] = e.gatherScale;
        send[i] = e.sendScale;
        seen[i] = e.seen;
        seenError[i] = e.seenError;
        gd[i] = Gd[leaves[i]].maxComponent();
    }

    // The links from reflecting sources, in the solver's receiver order, and an index by
    // source (counting sort: deterministic).
    BalanceLinks L;
    for (auto* v : {&L.receiver, &L.source}) v->reserve(links_.size());
    L.FV.reserve(links_.size());
    L.w.reserve(links_.size());
    for (const Link& l : links_) {
        if (!reflecting[l.source]) continue;
        if (L.receiver.empty() || L.receiver.back() != l.receiver)
            L.receiverStart.push_back(static_cast<int>(L.receiver.size()));
        L.receiver.push_back(l.receiver);
        L.source.push_back(l.source);
        L.FV.push_back(l.F * static_cast<double>(l.V));
        Vec3 w{0, 0, 0};
        if (cluster[l.receiver]) {  // linkDirection(R, S) in R's frame
            const Vec3 d = centre[l.source] - centre[l.receiver];
            const double len = glm::length(d);
            const auto& f = frame[slot[l.receiver]];
            if (len > 0) w = Vec3{glm::dot(f[0], d), glm::dot(f[1], d), glm::dot(f[2], d)} / len;
        }
        L.w.push_back(w);
    }
    const int M = static_cast<int>(L.receiver.size());
    L.receiverStart.push_back(M);
    L.sourceStart.assign(N + 1, 0);
    for (int k = 0; k < M; ++k) ++L.sourceStart[L.source[k] + 1];
    for (size_t n = 0; n < N; ++n) L.sourceStart[n + 1] += L.sourceStart[n];
    {
        std::vector<int> next(L.sourceStart.begin(), L.sourceStart.end() - 1);
        L.bySource.resize(M);
        for (int k = 0; k < M; ++k) L.bySource[next[L.source[k]]++] = k;
    }

    std::vector<double> x(N), xa(N), P(N), C(N);
    std::vector<Bins> bins(clusters.size());
    // Sums (weight 1) or area means of per-leaf values over every node (tree_walks.h).
    auto pull = [&](const std::vector<double>& leafValue, bool mean) {
        std::fill(x.begin(), x.end(), 0.0);
        std::fill(xa.begin(), xa.end(), 0.0);
        for (size_t i = 0; i < K; ++i) {
            x[leaves[i]] = mean ? leafValue[i] * area[leaves[i]] : leafValue[i];
            xa[leaves[i]] = area[leaves[i]];
        }
        pullUp(pre, parent, x, xa, mean);
    };

    bool settled = false;
    for (int it = 0; it < kBalanceIterations && !settled; ++it) {
        // --- Columns. W: the receivers' leaf areas weighted by their gather scales (x),
        // and per receiving cluster by direction bin, its polygons' W by their normals.
        std::vector<double> Ar(K);
        for (size_t i = 0; i < K; ++i) Ar[i] = area[leaves[i]] * gather[i];
        pull(Ar, /*mean=*/false);
        std::fill(bins.begin(), bins.end(), Bins{});
        for (size_t i = 0; i < roots.size(); ++i)
            for (int k = ancestorStart[i]; k < ancestorStart[i + 1]; ++k)
                for (int a = 0; a < 3; ++a)
                    bins[ancestor[k]][bin(ancestorNormal[k], a)] +=
                        x[roots[i]] * static_cast<double>(std::abs(ancestorNormal[k][a]));
        // P_s: what the links from s deliver per unit of what s sends (m^2).
        parallelFor(N, 1024, [&](size_t s) {
            double p = 0;
            for (int j = L.sourceStart[s]; j < L.sourceStart[s + 1]; ++j) {
                const int k = L.bySource[j], rc = L.receiver[k];
                double w = 0;
                if (cluster[rc]) {
                    const Bins& b = bins[slot[rc]];
                    for (int a = 0; a < 3; ++a) w += std::abs(L.w[k][a]) * b[bin(L.w[k], a)];
                } else {
                    w = x[rc];
                }
                p += L.FV[k] * w;
            }
            P[s] = p;
        });
        // C_m: P / A summed down from the root.
        for (int n : pre)
            C[n] = (parent[n] >= 0 ? C[parent[n]] : 0.0) +
                   (area[n] > 0 ? P[n] / area[n] : 0.0);  // guard: a zero-area node
        // Each send moved into what the leaf sees (+- 2 standard errors), then the sends
        // held at a geometric mean of 1 by area: rows and columns fix only the products
        // of gather and send scales, a common factor moves freely between them.
        const std::vector<double> before = send;
        double logSum = 0, areaSum = 0;
        for (size_t i = 0; i < K; ++i) {
            if (!moves[i] || !reflecting[leaves[i]] || !(seen[i] >= 0)) continue;
            const double c = C[leaves[i]] * send[i];
            const double lo = std::max(0.0, seen[i] - 2 * seenError[i]);
            const double hi = std::max(lo, std::min(1.0, seen[i] + 2 * seenError[i]));
            if (c > 0) send[i] *= std::clamp(c, lo, hi) / c;
            if (!(send[i] > 0)) continue;  // sees nothing: out of the mean (clamped below)
            logSum += area[leaves[i]] * std::log(send[i]);
            areaSum += area[leaves[i]];
        }
        // (A partial balance, of an inserted object's leaves against the fixed rest of
        // the scene, has no free factor: no gauge.)
        const double gauge = areaSum > 0 && firstNode == 0 ? std::exp(-logSum / areaSum) : 1.0;
        double change = 0, changeArea = 0;  // area-weighted mean relative change
        for (size_t i = 0; i < K; ++i) {
            if (!moves[i] || !reflecting[leaves[i]]) continue;
            send[i] = std::clamp(send[i] * gauge, 1 / kMaxRenormalisation, kMaxRenormalisation);
            change += area[leaves[i]] * std::abs(send[i] / before[i] - 1);
            changeArea += area[leaves[i]];
        }
        settled = !(changeArea > 0) || change < kBalanceTolerance * changeArea;

        // --- Rows: what each leaf gathers when every source sends its mean send scale.
        pull(send, /*mean=*/true);
        const std::vector<double> sourceSend = x;
        std::fill(x.begin(), x.end(), 0.0);
        std::fill(bins.begin(), bins.end(), Bins{});
        parallelFor(L.receiverStart.size() - 1, 64, [&](size_t i) {
            for (int k = L.receiverStart[i]; k < L.receiverStart[i + 1]; ++k) {
                const int rc = L.receiver[k];
                const double v = L.FV[k] * sourceSend[L.source[k]];
                if (!cluster[rc]) {
                    x[rc] += v;
                    continue;
                }
                for (int a = 0; a < 3; ++a)
                    bins[slot[rc]][bin(L.w[k], a)] += v * std::abs(L.w[k][a]);
            }
        });
        // Down: a root element takes what its cluster ancestors gathered, by its normal;
        // every element what its element ancestors gathered.
        parallelFor(roots.size(), 256, [&](size_t i) {
            for (int k = ancestorStart[i]; k < ancestorStart[i + 1]; ++k)
                for (int a = 0; a < 3; ++a)
                    x[roots[i]] += bins[ancestor[k]][bin(ancestorNormal[k], a)] *
                                   static_cast<double>(std::abs(ancestorNormal[k][a]));
        });
        for (int n : pre)
            if (!cluster[n] && parent[n] >= 0 && !cluster[parent[n]]) x[n] += x[parent[n]];
        boundedLeaves_ = 0;
        maxGather_ = 1;
        for (size_t i = 0; i < K; ++i) {
            if (moves[i]) gather[i] = rowScale(seen[i], seenError[i], x[leaves[i]], gd[i]);
            maxGather_ = std::max(maxGather_, x[leaves[i]]);
            if (std::abs(gather[i] - 1) > 0.05) ++boundedLeaves_;
        }
    }
    for (size_t i = 0; i < K; ++i) {
        Node& e = h_.nodes[leaves[i]];
        e.gatherScale = gather[i];
        e.sendScale = send[i];
    }
}

}  // namespace radiosity
