#include "radiosity/shared_gather.h"

#include <atomic>
#include <cmath>

#include "radiosity/detail/point_gather.h"
#include "radiosity/parallel.h"

namespace radiosity {

namespace {

/// Whether receiver `node`'s link l is gathered at the element's corners (see the header).
bool sharedLink(const Hierarchy& h, const Node& r, const Link& l) {
    if (r.isCluster() || r.vertexCount < 3) return false;
    const Node& s = h.nodes[l.source];
    return glm::length(s.centre - r.centre) > kSharedGatherFar * (r.radius + s.radius);
}

/// Corner c of element r moved a hair (1e-4 of the way) towards its centre, as
/// LeafMesh::insidePoint moves a vertex: rays and point location never start on an edge.
Vec3 samplePoint(const Node& r, int c) {
    return r.v[c] + 1e-4 * (r.centre - r.v[c]);
}

/// Weights of the samples of element r at x: the affine function through the samples'
/// values (least squares over a quad's four, exact over a triangle's three), evaluated at x.
/// With A the rows [1 u_c v_c] (u, v: coordinates in r's plane), the fit's value at
/// [1 u v] is sum_c a_c f_c with a = A (A^T A)^-1 [1 u v]^T; sum a_c = 1.
std::array<double, 4> affineWeights(const Node& r, const Vec3& x) {
    const int k = r.vertexCount;
    std::array<double, 4> a{0, 0, 0, 0};
    const Vec3 t1 = glm::normalize(r.v[1] - r.v[0]), t2 = glm::cross(r.normal, t1);
    double A[4][3], M[3][3] = {};
    for (int c = 0; c < k; ++c) {
        const Vec3 d = samplePoint(r, c) - r.centre;
        A[c][0] = 1;
        A[c][1] = glm::dot(d, t1);
        A[c][2] = glm::dot(d, t2);
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) M[i][j] += A[c][i] * A[c][j];
    }
    const Vec3 dx = x - r.centre;
    const double q[3] = {1, glm::dot(dx, t1), glm::dot(dx, t2)};
    // y = M^-1 q by Cramer's rule; a degenerate element (no area) takes the samples' mean.
    const double det = M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                       M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                       M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
    const double scale = M[1][1] * M[2][2];
    if (!(std::abs(det) > 1e-12 * std::max(scale, 1e-300)) || !std::isfinite(det)) {
        for (int c = 0; c < k; ++c) a[c] = 1.0 / k;
        return a;
    }
    double y[3];
    for (int col = 0; col < 3; ++col) {
        double m[3][3];
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) m[i][j] = j == col ? q[i] : M[i][j];
        y[col] = (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                  m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                  m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])) /
                 det;
    }
    for (int c = 0; c < k; ++c) a[c] = A[c][0] * y[0] + A[c][1] * y[1] + A[c][2] * y[2];
    return a;
}

/// The element receivers on the points' chains that hold far links, each given its
/// vertexCount consecutive samples: first[node] (-1: none), in order of first meeting; and
/// the indices of its near links, gathered per point (nodes[k]'s in [nearStart[k],
/// nearStart[k + 1]) of nearIndex; ordinal[node] = k): a point then never reads the far
/// links' sources, thousands on a wall.
struct SampleLayout {
    std::vector<int> first, ordinal;
    std::vector<int> nodes;
    std::vector<size_t> nearStart{0};
    std::vector<int> nearIndex;
    std::vector<int> leafOf;  ///< per point: its leaf (-1: no gather)
    /// Per node: a leaf whose corners also gather its element ancestors' links that are
    /// near them but far from it (nearAncestorFarLeaf).
    std::vector<char> leafShares;
    /// For such a leaf, nearAncestorFarLeaf of each near link of its ancestors (parent first, each
    /// in forNearLinks' order), from atLeafStart[leaf]: decided once per leaf, not at each
    /// of its points, where reading each link's source node (a cache miss) took most of the
    /// points' gather on a real stair hall.
    std::vector<size_t> atLeafStart;
    std::vector<char> atLeaf;
    int samples = 0;
    size_t shared = 0, near = 0, leafShared = 0;
};

/// Whether link l of element ancestor `a` of leaf `leaf` is gathered at the leaf's corners:
/// near the ancestor (a large wall's link to a source beside it), but far from the leaf.
bool nearAncestorFarLeaf(const Hierarchy& h, int leaf, int a, const Link& l) {
    if (a == leaf || h.nodes[a].isCluster()) return false;
    return !sharedLink(h, h.nodes[a], l) && sharedLink(h, h.nodes[leaf], l);
}

/// The links of node `node` that a point gathers itself (not at node's corners): its near
/// links' indices where it has samples, all of them otherwise; f(j) for each index j.
template <class F>
void forNearLinks(const SampleLayout& s, int node, size_t count, const F& f) {
    const int k = s.ordinal[node];
    if (k < 0) {
        for (size_t j = 0; j < count; ++j) f(j);
        return;
    }
    for (size_t j = s.nearStart[k]; j != s.nearStart[k + 1]; ++j)
        f(static_cast<size_t>(s.nearIndex[j]));
}

/// f(link, atLeaf) for each link that a point of `leaf` gathers itself along its chain
/// (leaf first, then its ancestors: forNearLinks); atLeaf: the link is gathered at the
/// leaf's corners instead (SampleLayout::atLeaf).
template <class F>
void forChainNearLinks(const HierarchicalSolver& solver, const SampleLayout& s, int leaf,
                       const F& f) {
    const Hierarchy& h = solver.hierarchy();
    const char* atLeaf = s.leafShares[leaf] ? s.atLeaf.data() + s.atLeafStart[leaf] : nullptr;
    for (int node = leaf; node >= 0; node = h.nodes[node].parent) {
        const bool ancestor = node != leaf && atLeaf;
        const auto links = solver.linksOf(node);
        forNearLinks(s, node, links.size(), [&](size_t j) { f(links[j], ancestor && *atLeaf++); });
    }
}

/// Gives a leaf corners of its own for its element ancestors' links that are near them but
/// far from it (nearAncestorFarLeaf), where that is cheaper than gathering them at each point: when
/// more than twice as many points lie in the leaf as it has corners. A wall that cannot be
/// split further can hold tens of thousands of links to the small parts of a piece of
/// furniture beside it, all near the whole wall; each of the wall's points gathered them all
/// (a real stair hall: 79 k links, 160 M terms, 2 minutes). From a leaf of the wall most are
/// far, and the affine fit over the leaf holds as over any element (shared_gather.h).
void shareAtLeaves(const HierarchicalSolver& solver, std::span<const GatherPoint> points,
                   SampleLayout& s) {
    const Hierarchy& h = solver.hierarchy();
    s.leafShares.assign(h.nodes.size(), 0);
    s.atLeafStart.assign(h.nodes.size(), 0);
    std::vector<int> count(h.nodes.size(), 0);
    std::vector<int> leaves;
    for (size_t i = 0; i < points.size(); ++i)
        if (s.leafOf[i] >= 0 && count[static_cast<size_t>(s.leafOf[i])]++ == 0)
            leaves.push_back(s.leafOf[i]);
    for (const int leaf : leaves) {
        const Node& L = h.nodes[leaf];
        if (L.isCluster() || L.vertexCount < 3 || count[leaf] <= 2 * L.vertexCount) continue;
        size_t mid = 0;
        const size_t start = s.atLeaf.size();
        for (int a = L.parent; a >= 0; a = h.nodes[a].parent) {
            const auto links = solver.linksOf(a);
            forNearLinks(s, a, links.size(), [&](size_t j) {
                const bool shared = nearAncestorFarLeaf(h, leaf, a, links[j]);
                s.atLeaf.push_back(shared ? 1 : 0);
                mid += shared ? 1 : 0;
            });
        }
        s.leafShares[leaf] = mid > 0;
        s.leafShared += mid;
        if (mid == 0) s.atLeaf.resize(start);
        s.atLeafStart[leaf] = start;
        if (mid == 0 || s.first[leaf] >= 0) continue;
        // Corners of its own (it had no far links of its own): all its links stay near.
        s.first[leaf] = s.samples;
        s.ordinal[leaf] = static_cast<int>(s.nodes.size());
        s.nodes.push_back(leaf);
        s.samples += L.vertexCount;
        const size_t own = solver.linksOf(leaf).size();
        for (size_t j = 0; j < own; ++j) s.nearIndex.push_back(static_cast<int>(j));
        s.nearStart.push_back(s.nearIndex.size());
    }
}

SampleLayout layOutSamples(const HierarchicalSolver& solver, std::span<const GatherPoint> points) {
    const Hierarchy& h = solver.hierarchy();
    SampleLayout s;
    s.first.assign(h.nodes.size(), -1);
    s.ordinal.assign(h.nodes.size(), -1);
    std::vector<char> seen(h.nodes.size(), 0);
    s.leafOf.assign(points.size(), -1);
    for (size_t i = 0; i < points.size(); ++i) {
        if (points[i].polygon < 0) continue;
        s.leafOf[i] = h.locateLeaf(points[i].polygon, points[i].x);
        for (int node = s.leafOf[i]; node >= 0; node = h.nodes[node].parent) {
            if (seen[node]) break;  // its ancestors were met with it
            seen[node] = 1;
            const auto links = solver.linksOf(node);
            size_t shared = 0;
            for (const Link& l : links) shared += sharedLink(h, h.nodes[node], l) ? 1 : 0;
            s.shared += shared;
            s.near += links.size() - shared;
            if (shared == 0) continue;
            s.first[node] = s.samples;
            s.ordinal[node] = static_cast<int>(s.nodes.size());
            s.nodes.push_back(node);
            s.samples += h.nodes[node].vertexCount;
            for (size_t k = 0; k < links.size(); ++k)
                if (!sharedLink(h, h.nodes[node], links[k]))
                    s.nearIndex.push_back(static_cast<int>(k));
            s.nearStart.push_back(s.nearIndex.size());
        }
    }
    shareAtLeaves(solver, points, s);
    return s;
}

}  // namespace

SharedGather sharedFinalGather(const HierarchicalSolver& solver,
                               std::span<const GatherPoint> points, int partialRays,
                               const ProgressFn& progress, Clock::time_point raysUntil) {
    const Hierarchy& h = solver.hierarchy();
    SharedGather out;
    const SampleLayout layout = layOutSamples(solver, points);
    ProgressMeter meter(progress, "final gather (element corners, then points)",
                        layout.nodes.size() + points.size());
    out.sharedLinks = layout.shared;
    out.nearLinks = layout.near;
    out.leafSharedLinks = layout.leafShared;
    std::atomic<uint64_t> rays{0};
    std::atomic<size_t> withoutRays{0};
    // Rays per PARTIAL link for an item begun now: none once raysUntil has passed.
    auto raysNow = [&](size_t items) {
        if (Clock::now() < raysUntil) return std::clamp(partialRays, 0, 64);
        withoutRays += items;
        return 0;
    };
    auto record = [](std::vector<GatherWeight>& v) {
        return [&v](int s, double w) { v.push_back({s, static_cast<float>(w)}); };
    };
    // The corners' gathers over the far links: a block per element, its corners in order.
    out.sampleTerms.items.resize(static_cast<size_t>(layout.samples));
    out.sampleTerms.blocks.resize(layout.nodes.size());
    parallelFor(layout.nodes.size(), 1, [&](size_t i) {
        const int node = layout.nodes[i];
        const Node& r = h.nodes[node];
        const Vec3& n = solver.scene().polygons[r.polygon].normal;
        const int pr = raysNow(static_cast<size_t>(r.vertexCount));
        uint64_t cast = 0;
        const size_t first = static_cast<size_t>(layout.first[node]);
        out.sampleTerms.fillBlock(
            i, first, first + static_cast<size_t>(r.vertexCount),
            [&](size_t sample, std::vector<GatherWeight>& terms) {
                const int c = static_cast<int>(sample - first);
                const Vec3 x = samplePoint(r, c);
                Rng rng(static_cast<uint64_t>(node) * 4 + c + 0x5A3Dull);
                auto acc = record(terms);
                for (const Link& l : solver.linksOf(node))
                    if (detail::mayCarry(l) && sharedLink(h, r, l))
                        detail::gatherLink(solver, r.polygon, x, n, l, pr, rng, cast, acc);
                if (!layout.leafShares[node]) return;
                forChainNearLinks(solver, layout, node, [&](const Link& l, bool atLeaf) {
                    if (atLeaf && detail::mayCarry(l))
                        detail::gatherLink(solver, r.polygon, x, n, l, pr, rng, cast, acc);
                });
            });
        rays += cast;
        meter.add(1);
    });
    // Each point's near links, and its references to the corners above it: a block per run
    // of kPointBlock points.
    constexpr size_t kPointBlock = 64;
    const size_t blocks = (points.size() + kPointBlock - 1) / kPointBlock;
    out.pointTerms.items.resize(points.size());
    out.pointTerms.blocks.resize(blocks);
    out.refs.items.resize(points.size());
    out.refs.blocks.resize(blocks);
    parallelFor(blocks, 1, [&](size_t b) {
        const size_t from = b * kPointBlock, to = std::min(points.size(), from + kPointBlock);
        uint64_t cast = 0;
        const int pr = raysNow(to - from);
        out.pointTerms.fillBlock(b, from, to, [&](size_t i, std::vector<GatherWeight>& terms) {
            const GatherPoint& p = points[i];
            if (layout.leafOf[i] < 0) return;
            const Vec3& n = solver.scene().polygons[p.polygon].normal;
            Rng rng = detail::gatherRng(p.seed);
            auto acc = record(terms);
            forChainNearLinks(solver, layout, layout.leafOf[i], [&](const Link& l, bool atLeaf) {
                if (!atLeaf && detail::mayCarry(l))
                    detail::gatherLink(solver, p.polygon, p.x, n, l, pr, rng, cast, acc);
            });
        });
        out.refs.fillBlock(b, from, to, [&](size_t i, std::vector<SharedGather::SampleRef>& refs) {
            if (layout.leafOf[i] < 0) return;
            for (int node = layout.leafOf[i]; node >= 0; node = h.nodes[node].parent) {
                if (layout.ordinal[node] < 0) continue;
                const int first = layout.first[node];
                const auto a = affineWeights(h.nodes[node], points[i].x);
                for (int c = 0; c < h.nodes[node].vertexCount; ++c)
                    refs.push_back({first + c, static_cast<float>(a[c])});
            }
        });
        rays += cast;
        meter.add(to - from);
    });
    out.rays = rays.load();
    out.withoutRays = withoutRays.load();
    return out;
}

namespace {

/// out[i * L + l] += the gather of point i with values(node)[l] the radiosity node reflects
/// for "light" l.
template <class Values>
void addGather(const SharedGather& g, int L, const Values& values, Rgb* out) {
    std::vector<Rgb> S(g.samples() * static_cast<size_t>(L));
    parallelFor(g.samples(), 256, [&](size_t s) {
        Rgb* v = S.data() + s * L;
        for (const GatherWeight& t : g.sampleTerms[s]) {
            const auto R = values(t.node);
            for (int l = 0; l < L; ++l) v[l] += R[l] * t.w;
        }
    });
    parallelFor(g.points(), 256, [&](size_t i) {
        Rgb* h = out + i * L;
        for (const GatherWeight& t : g.pointTerms[i]) {
            const auto R = values(t.node);
            for (int l = 0; l < L; ++l) h[l] += R[l] * t.w;
        }
        for (const SharedGather::SampleRef& r : g.refs[i]) {
            const Rgb* v = S.data() + static_cast<size_t>(r.sample) * L;
            for (int l = 0; l < L; ++l) h[l] += v[l] * r.weight;
        }
    });
}

}  // namespace

void SharedGather::addResponses(const LightResponses& responses, Rgb* out) const {
    addGather(
        *this, responses.lights(), [&](int node) { return responses.reflected(node); }, out);
}

void SharedGather::addIndirect(const HierarchicalSolver& solver, Rgb* out) const {
    const auto& nodes = solver.hierarchy().nodes;
    addGather(
        *this, 1,
        [&](int node) {
            const Node& S = nodes[static_cast<size_t>(node)];
            return std::array<Rgb, 1>{S.emitting ? S.B - S.E : S.B};
        },
        out);
}

}  // namespace radiosity
