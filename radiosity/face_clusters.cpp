#include "radiosity/face_clusters.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <queue>
#include <unordered_map>
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

struct CornerKey {
    double x, y, z;
    bool operator==(const CornerKey& k) const { return x == k.x && y == k.y && z == k.z; }
};
struct CornerHash {
    size_t operator()(const CornerKey& k) const {
        uint64_t h = 1469598103934665603ull;
        for (double d : {k.x, k.y, k.z}) {
            uint64_t bits;
            std::memcpy(&bits, &d, sizeof bits);
            h = (h ^ bits) * 1099511628211ull;
            h ^= h >> 29;
        }
        return static_cast<size_t>(h);
    }
};

using Adjacency = std::vector<std::vector<std::pair<int, double>>>;  // (neighbour, shared length)

void addShared(std::vector<std::pair<int, double>>& list, int other, double length) {
    for (auto& [n, l] : list)
        if (n == other) {
            l += length;
            return;
        }
    list.emplace_back(other, length);
}

/// Polygons that share an edge (both corners equal to the last bit), of the same object and
/// neither a lamp's face.
Adjacency sharedEdges(std::span<const Polygon> polygons, size_t capacity) {
    std::unordered_map<CornerKey, int, CornerHash> corners;
    corners.reserve(polygons.size() * 2);
    const auto cornerId = [&](const Vec3& v) {
        return corners.try_emplace(CornerKey{v.x, v.y, v.z}, static_cast<int>(corners.size()))
            .first->second;
    };
    std::unordered_map<uint64_t, std::vector<int>> edges;
    edges.reserve(polygons.size() * 2);
    for (size_t p = 0; p < polygons.size(); ++p) {
        const Polygon& P = polygons[p];
        if (P.light >= 0) continue;
        for (int i = 0; i < P.vertexCount; ++i) {
            const uint64_t a = static_cast<uint32_t>(cornerId(P.v[i]));
            const uint64_t b = static_cast<uint32_t>(cornerId(P.v[(i + 1) % P.vertexCount]));
            if (a == b) continue;
            edges[std::min(a, b) << 32 | std::max(a, b)].push_back(static_cast<int>(p));
        }
    }
    Adjacency adj(capacity);
    for (const auto& [key, faces] : edges) {
        if (faces.size() < 2 || faces.size() > 8) continue;  // a boundary, or a fan of sheets
        const Polygon& P0 = polygons[faces[0]];
        double length = 0;
        for (int i = 0; i < P0.vertexCount && length == 0; ++i) {
            const Vec3& a = P0.v[i];
            const Vec3& b = P0.v[(i + 1) % P0.vertexCount];
            const uint64_t ia = static_cast<uint32_t>(cornerId(a)),
                           ib = static_cast<uint32_t>(cornerId(b));
            if ((std::min(ia, ib) << 32 | std::max(ia, ib)) == key) length = glm::length(b - a);
        }
        for (size_t i = 0; i < faces.size(); ++i)
            for (size_t j = i + 1; j < faces.size(); ++j) {
                const int f = faces[i], g = faces[j];
                if (f == g || polygons[f].object != polygons[g].object) continue;
                addShared(adj[f], g, length);
                addShared(adj[g], f, length);
            }
    }
    return adj;
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
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> heap;
    const auto offer = [&](int a, int b, double shared) {
        const double c = mergeCost(stats[a], stats[b], shared, options, nullptr);
        if (std::isfinite(c)) heap.push({c, std::min(a, b), std::max(a, b)});
    };
    for (int f = 0; f < n; ++f)
        for (const auto& [g, len] : adj[f])
            if (f < g) offer(f, g, len);

    while (!heap.empty()) {
        const Candidate top = heap.top();
        heap.pop();
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
        for (int part : {top.a, top.b}) {
            for (const auto& [x, len] : adj[part]) {
                if (x == top.a || x == top.b) continue;
                addShared(adj[c], x, len);
                auto& back = adj[x];
                back.erase(std::remove_if(
                               back.begin(), back.end(),
                               [&](const auto& e) { return e.first == top.a || e.first == top.b; }),
                           back.end());
            }
            adj[part] = {};
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
