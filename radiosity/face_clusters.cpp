#include "radiosity/face_clusters.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <utility>

namespace radiosity {

namespace {

/// What a face cluster keeps to price a merge: sums over its polygons, so that a merge
/// adds two records.
struct Stats {
    double area = 0;
    Vec3 vectorArea{0, 0, 0};
    std::array<double, 6> moment{};  ///< sum A n n^T: xx, yy, zz, xy, xz, yz
    Vec3 s1{0, 0, 0};                ///< sum w p over corners (w: the corner's area share)
    std::array<double, 6> s2{};      ///< sum w p p^T
    double perimeter = 0;
    Vec3 coneAxis{0, 0, 1};
    double coneAngle = 0;
    int object = -1;
};

double quadratic(const std::array<double, 6>& m, const Vec3& v) {
    return m[0] * v.x * v.x + m[1] * v.y * v.y + m[2] * v.z * v.z +
           2 * (m[3] * v.x * v.y + m[4] * v.x * v.z + m[5] * v.y * v.z);
}

void addOuter(std::array<double, 6>& m, const Vec3& v, double w) {
    m[0] += w * v.x * v.x;
    m[1] += w * v.y * v.y;
    m[2] += w * v.z * v.z;
    m[3] += w * v.x * v.y;
    m[4] += w * v.x * v.z;
    m[5] += w * v.y * v.z;
}

Stats polygonStats(const Polygon& p) {
    Stats s;
    s.area = p.area;
    s.vectorArea = p.area * p.normal;
    addOuter(s.moment, p.normal, p.area);
    const double w = p.area / p.vertexCount;
    for (int i = 0; i < p.vertexCount; ++i) {
        s.s1 += w * p.v[i];
        addOuter(s.s2, p.v[i], w);
        s.perimeter += glm::length(p.v[(i + 1) % p.vertexCount] - p.v[i]);
    }
    s.coneAxis = p.normal;
    s.object = p.object;
    return s;
}

/// The two records summed; the perimeter less twice the boundary they share.
Stats merged(const Stats& a, const Stats& b, double shared) {
    Stats m;
    m.area = a.area + b.area;
    m.vectorArea = a.vectorArea + b.vectorArea;
    m.s1 = a.s1 + b.s1;
    for (int i = 0; i < 6; ++i) {
        m.moment[i] = a.moment[i] + b.moment[i];
        m.s2[i] = a.s2[i] + b.s2[i];
    }
    m.perimeter = std::max(0.0, a.perimeter + b.perimeter - 2 * shared);
    m.object = a.object;
    const double len = glm::length(m.vectorArea);
    m.coneAxis = len > 0 ? m.vectorArea / len : a.coneAxis;
    // A cone about the new axis that holds both parts' cones.
    const auto reach = [&](const Stats& s) {
        return std::acos(std::clamp(glm::dot(m.coneAxis, s.coneAxis), -1.0, 1.0)) + s.coneAngle;
    };
    m.coneAngle = std::min(std::numbers::pi, std::max(reach(a), reach(b)));
    return m;
}

/// The merge cost of the header; infinity where the merge is refused.
double mergeCost(const Stats& a, const Stats& b, double shared, const FaceClusterOptions& o,
                 Stats* out) {
    constexpr double kRefused = std::numeric_limits<double>::infinity();
    if (glm::dot(a.coneAxis, b.coneAxis) <= 0) return kRefused;  // opposite sides of a sheet
    const Stats m = merged(a, b, shared);
    const double len = glm::length(m.vectorArea);
    if (!(m.area > 0) || !(len > 1e-12 * m.area) || m.coneAngle > o.maxConeAngle) return kRefused;
    const Vec3 n = m.vectorArea / len;
    const double eDir = std::max(0.0, (m.area - 2 * len + quadratic(m.moment, n)) / m.area);
    const Vec3 mu = m.s1 / m.area;
    const double spread = quadratic(m.s2, n) / m.area - glm::dot(mu, n) * glm::dot(mu, n);
    const double eFit = std::max(0.0, spread) / m.area;
    const double eShape =
        std::max(0.0, m.perimeter * m.perimeter / (4 * std::numbers::pi * m.area) - 1);
    if (out) *out = m;
    return eDir + eFit + o.shapeWeight * eShape;
}

using Adjacency = std::vector<std::vector<std::pair<int, double>>>;  // (neighbour, shared length)

void addShared(std::vector<std::pair<int, double>>& list, int other, double length) {
    for (auto& [n, l] : list)
        if (n == other) {
            l += length;
            return;
        }
    list.emplace_back(other, length);
}

/// Every corner of the reflecting polygons numbered so that corners equal to the last bit
/// share a number: the corners sorted by their coordinates' bits (sorting 10^6 corners
/// costs a fifth of hashing them into a map of vectors, bench/RESULTS.md 2026-11-27, eighth
/// session). cornerId[k] is the number of corner k of the concatenated corner lists,
/// polygon by polygon (first[p]: where polygon p's begin).
struct CornerIds {
    std::vector<int> first, id;
};

CornerIds numberCorners(std::span<const Polygon> polygons) {
    CornerIds c;
    c.first.resize(polygons.size() + 1, 0);
    for (size_t p = 0; p < polygons.size(); ++p)
        c.first[p + 1] = c.first[p] + (polygons[p].light >= 0 ? 0 : polygons[p].vertexCount);
    const size_t count = static_cast<size_t>(c.first.back());
    struct Corner {
        std::array<uint64_t, 3> bits;
        int index;
    };
    std::vector<Corner> corners(count);
    for (size_t p = 0; p < polygons.size(); ++p)
        for (int k = c.first[p]; k < c.first[p + 1]; ++k) {
            const Vec3& v = polygons[p].v[k - c.first[p]];
            Corner& x = corners[static_cast<size_t>(k)];
            std::memcpy(x.bits.data(), &v.x, 8);
            std::memcpy(x.bits.data() + 1, &v.y, 8);
            std::memcpy(x.bits.data() + 2, &v.z, 8);
            x.index = k;
        }
    tbb::parallel_sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) {
        return a.bits != b.bits ? a.bits < b.bits : a.index < b.index;
    });
    c.id.resize(count);
    int next = -1;
    for (size_t i = 0; i < count; ++i) {
        if (i == 0 || corners[i].bits != corners[i - 1].bits) ++next;
        c.id[static_cast<size_t>(corners[i].index)] = next;
    }
    return c;
}

/// Polygons that share an edge (both corners equal to the last bit), of the same object and
/// neither a lamp's face.
Adjacency sharedEdges(std::span<const Polygon> polygons, size_t capacity) {
    const CornerIds corners = numberCorners(polygons);
    struct EdgeUse {
        uint64_t key;  ///< the two corner numbers, smaller first
        int polygon;
        double length;
    };
    std::vector<EdgeUse> uses;
    uses.reserve(corners.id.size());
    for (size_t p = 0; p < polygons.size(); ++p) {
        const int f = corners.first[p], count = corners.first[p + 1] - f;
        for (int i = 0; i < count; ++i) {
            const uint64_t a = static_cast<uint32_t>(corners.id[static_cast<size_t>(f + i)]);
            const uint64_t b =
                static_cast<uint32_t>(corners.id[static_cast<size_t>(f + (i + 1) % count)]);
            if (a == b) continue;
            // The same length from every polygon on the edge: its corners are equal.
            const double length = glm::length(polygons[p].v[(i + 1) % count] - polygons[p].v[i]);
            uses.push_back({std::min(a, b) << 32 | std::max(a, b), static_cast<int>(p), length});
        }
    }
    tbb::parallel_sort(uses.begin(), uses.end(), [](const EdgeUse& a, const EdgeUse& b) {
        return a.key != b.key ? a.key < b.key : a.polygon < b.polygon;
    });
    Adjacency adj(capacity);
    for (size_t begin = 0, end = 0; begin < uses.size(); begin = end) {
        while (end < uses.size() && uses[end].key == uses[begin].key) ++end;
        if (end - begin < 2 || end - begin > 8) continue;  // a boundary, or a fan of sheets
        for (size_t i = begin; i < end; ++i)
            for (size_t j = i + 1; j < end; ++j) {
                const int f = uses[i].polygon, g = uses[j].polygon;
                if (f == g || polygons[f].object != polygons[g].object) continue;
                addShared(adj[f], g, uses[begin].length);
                addShared(adj[g], f, uses[begin].length);
            }
    }
    return adj;
}

/// The neighbours of clusters a and b, for their union: each once, sorted, with the
/// lengths it shares with a and with b summed (a's first). Sorting keeps a merge at
/// O(d log d) for clusters of d neighbours, where adding one neighbour at a time to the
/// union's list was O(d^2): a stair hall's chandelier of 167 k triangles made clusters of
/// thousands of neighbours.
std::vector<std::pair<int, double>> mergedNeighbours(const Adjacency& adj, int a, int b) {
    std::vector<std::pair<int, double>> all;
    all.reserve(adj[a].size() + adj[b].size());
    for (int part : {a, b})
        for (const auto& e : adj[part])
            if (e.first != a && e.first != b) all.push_back(e);
    std::stable_sort(all.begin(), all.end(),
                     [](const auto& l, const auto& r) { return l.first < r.first; });
    std::vector<std::pair<int, double>> out;
    out.reserve(all.size());
    for (const auto& e : all) {
        if (!out.empty() && out.back().first == e.first)
            out.back().second += e.second;
        else
            out.push_back(e);
    }
    return out;
}

}  // namespace

void FaceClusterForest::polygonsUnder(int t, std::vector<int>& out) const {
    std::vector<int> stack{t};
    while (!stack.empty()) {
        const int x = stack.back();
        stack.pop_back();
        if (isPolygon(x)) {
            out.push_back(x);
            continue;
        }
        const auto& m = merges[static_cast<size_t>(x - polygons)];
        stack.push_back(m[1]);  // left subtree first
        stack.push_back(m[0]);
    }
}

FaceClusterForest buildFaceClusters(std::span<const Polygon> polygons,
                                    const FaceClusterOptions& options) {
    const int n = static_cast<int>(polygons.size());
    FaceClusterForest forest;
    forest.polygons = n;
    const size_t capacity = 2 * static_cast<size_t>(n);
    Adjacency adj = sharedEdges(polygons, capacity);
    std::vector<Stats> stats;
    stats.reserve(capacity);
    for (const Polygon& p : polygons) stats.push_back(polygonStats(p));
    std::vector<char> alive(capacity, 0);
    std::fill(alive.begin(), alive.begin() + n, 1);

    struct Candidate {
        double cost;
        int a, b;
        bool operator>(const Candidate& c) const {
            if (cost != c.cost) return cost > c.cost;
            return a != c.a ? a > c.a : b > c.b;  // deterministic order for ties
        }
    };
    // A binary heap of candidates, least first. A merge leaves its parts' other candidates
    // in it, stale; they are dropped when popped, and all at once when they outnumber the
    // live ones: on a reconstructed mesh they made the heap several times its live size,
    // and its sift-down was half of the clustering's time (bench/RESULTS.md, 2026-11-28,
    // sixteenth session). The live candidates, and so the merges, are the same either way.
    std::vector<Candidate> heap;
    size_t stale = 0;  // an upper estimate of the stale candidates in the heap
    const std::greater<> later;
    const auto offer = [&](int a, int b, double shared) {
        const double c = mergeCost(stats[a], stats[b], shared, options, nullptr);
        if (!std::isfinite(c)) return;
        heap.push_back({c, std::min(a, b), std::max(a, b)});
        std::push_heap(heap.begin(), heap.end(), later);
    };
    const auto dropStale = [&] {
        std::erase_if(heap, [&](const Candidate& c) { return !alive[c.a] || !alive[c.b]; });
        std::make_heap(heap.begin(), heap.end(), later);
        stale = 0;
    };
    for (int f = 0; f < n; ++f)
        for (const auto& [g, len] : adj[f])
            if (f < g) offer(f, g, len);

    while (!heap.empty()) {
        std::pop_heap(heap.begin(), heap.end(), later);
        const Candidate top = heap.back();
        heap.pop_back();
        if (!alive[top.a] || !alive[top.b]) continue;  // a part was merged since
        double shared = 0;
        for (const auto& [x, len] : adj[top.a])
            if (x == top.b) shared = len;
        Stats m;
        mergeCost(stats[top.a], stats[top.b], shared, options, &m);
        const int c = n + static_cast<int>(forest.merges.size());
        forest.merges.push_back({top.a, top.b});
        stats.push_back(m);
        alive[top.a] = alive[top.b] = 0;
        alive[c] = 1;
        stale += adj[top.a].size() + adj[top.b].size();
        if (heap.size() > options.dropStaleAbove && 2 * stale > heap.size()) dropStale();
        adj[c] = mergedNeighbours(adj, top.a, top.b);
        adj[top.a] = {};
        adj[top.b] = {};
        for (const auto& [x, len] : adj[c]) {
            auto& back = adj[x];
            back.erase(
                std::remove_if(back.begin(), back.end(),
                               [&](const auto& e) { return e.first == top.a || e.first == top.b; }),
                back.end());
        }
        for (const auto& [x, len] : adj[c]) {
            adj[x].emplace_back(c, len);
            offer(c, x, len);
        }
    }
    for (int t = 0; t < n + static_cast<int>(forest.merges.size()); ++t)
        if (alive[t]) forest.roots.push_back(t);
    return forest;
}

}  // namespace radiosity
