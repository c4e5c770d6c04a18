#include "radiosity/leaf_mesh.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace radiosity {

namespace {

// Exact key of a corner position: the bits of its coordinates.
struct CornerKey {
    double x, y, z;
    bool operator==(const CornerKey& o) const {
        return std::memcmp(&x, &o.x, 3 * sizeof(double)) == 0;
    }
};

struct CornerKeyHash {
    size_t operator()(const CornerKey& k) const {
        uint64_t b[3];
        std::memcpy(b, &k.x, sizeof b);
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (uint64_t w : b) h = (h ^ w) * 0xbf58476d1ce4e5b9ull + (h >> 29);
        return static_cast<size_t>(h);
    }
};

}  // namespace

LeafMesh::LeafMesh(const Hierarchy& h) : LeafMesh(h, 0) {}

LeafMesh::LeafMesh(const Hierarchy& h, int firstNode) : h_(h), corners_(h.nodes.size()) {
    // The vertices at one position, each with the normal of the polygon that made it.
    std::unordered_map<CornerKey, std::vector<int>, CornerKeyHash> index;
    for (size_t n = 0; n < static_cast<size_t>(std::max(firstNode, 0)) && n < h.nodes.size(); ++n)
        corners_[n] = {-1, -1, -1, -1};
    for (size_t n = static_cast<size_t>(std::max(firstNode, 0)); n < h.nodes.size(); ++n) {
        corners_[n] = {-1, -1, -1, -1};
        const Node& e = h.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        for (int i = 0; i < e.vertexCount; ++i) {
            // +0.0 folds -0.0 into 0.0 so that the bit patterns of equal corners agree.
            const CornerKey key{e.v[i].x + 0.0, e.v[i].y + 0.0, e.v[i].z + 0.0};
            std::vector<int>& here = index[key];
            int id = -1;
            for (int v : here) {
                const Node& owner = h.nodes[ownerLeaf_[v]];
                if (owner.polygon == e.polygon || glm::dot(owner.normal, e.normal) >= kSmoothCos) {
                    id = v;
                    break;
                }
            }
            if (id < 0) {
                id = static_cast<int>(vertices_.size());
                here.push_back(id);
                vertices_.push_back({e.v[i], e.polygon});
                ownerLeaf_.push_back(static_cast<int>(n));
            }
            corners_[n][i] = id;
        }
    }
}

std::array<double, 4> LeafMesh::weights(int leaf, const Vec3& x) const {
    const Node& e = h_.nodes[leaf];
    const auto& v = e.v;
    if (e.vertexCount == 3) {
        // Barycentric coordinates from signed sub-triangle areas along the normal.
        const double a0 = glm::dot(glm::cross(v[1] - x, v[2] - x), e.normal);
        const double a1 = glm::dot(glm::cross(v[2] - x, v[0] - x), e.normal);
        const double a2 = glm::dot(glm::cross(v[0] - x, v[1] - x), e.normal);
        double w0 = std::max(a0, 0.0), w1 = std::max(a1, 0.0), w2 = std::max(a2, 0.0);
        const double sum = w0 + w1 + w2;
        // sum > 0 for any non-degenerate triangle (the loader rejects degenerate faces);
        // the guard keeps a zero-area leaf from producing NaN.
        if (!(sum > 0)) return {1.0 / 3, 1.0 / 3, 1.0 / 3, 0};
        return {w0 / sum, w1 / sum, w2 / sum, 0};
    }
    // Inverse of the bilinear map p(s,t) = (1-s)(1-t)v0 + s(1-t)v1 + st v2 + (1-s)t v3 by
    // Gauss-Newton on the plane (the quad is planar and convex, so the map is one-to-one and
    // a few steps from the centre converge to rounding).
    double s = 0.5, t = 0.5;
    for (int it = 0; it < 8; ++it) {
        const Vec3 p =
            (1 - s) * (1 - t) * v[0] + s * (1 - t) * v[1] + s * t * v[2] + (1 - s) * t * v[3];
        const Vec3 r = p - x;
        const Vec3 ds = (1 - t) * (v[1] - v[0]) + t * (v[2] - v[3]);
        const Vec3 dt = (1 - s) * (v[3] - v[0]) + s * (v[2] - v[1]);
        const double a = glm::dot(ds, ds), b = glm::dot(ds, dt), c = glm::dot(dt, dt);
        const double det = a * c - b * b;
        if (!(det > 1e-30 * a * c) || !(det > 0)) break;  // degenerate: keep the estimate
        const double gs = glm::dot(ds, r), gt = glm::dot(dt, r);
        const double stepS = (c * gs - b * gt) / det, stepT = (a * gt - b * gs) / det;
        s = std::clamp(s - stepS, 0.0, 1.0);
        t = std::clamp(t - stepT, 0.0, 1.0);
        if (std::abs(stepS) + std::abs(stepT) < 1e-12) break;
    }
    return {(1 - s) * (1 - t), s * (1 - t), s * t, (1 - s) * t};
}

Rgb LeafMesh::interpolate(const std::vector<Rgb>& values, int polygon, const Vec3& x) const {
    const int leaf = h_.locateLeaf(polygon, x);
    const auto w = weights(leaf, x);
    const auto& c = corners_[leaf];
    Rgb out;
    for (int i = 0; i < h_.nodes[leaf].vertexCount; ++i) out += w[i] * values[c[i]];
    return out;
}

std::vector<Rgb> LeafMesh::averageOfLeaves(const std::function<Rgb(int leaf)>& leafValue) const {
    std::vector<Rgb> sum(vertices_.size());
    std::vector<double> area(vertices_.size(), 0.0);
    for (size_t n = 0; n < corners_.size(); ++n) {
        if (corners_[n][0] < 0) continue;
        const Node& e = h_.nodes[n];
        const Rgb b = leafValue(static_cast<int>(n));
        for (int i = 0; i < e.vertexCount; ++i) {
            sum[corners_[n][i]] += e.area * b;
            area[corners_[n][i]] += e.area;
        }
    }
    for (size_t v = 0; v < sum.size(); ++v)
        if (area[v] > 0) sum[v] = (1.0 / area[v]) * sum[v];
    return sum;
}

Vec3 LeafMesh::insidePoint(int v) const {
    const Node& e = h_.nodes[ownerLeaf_[v]];
    const Vec3& p = vertices_[v].position;
    return p + 1e-4 * (e.centre - p);
}

}  // namespace radiosity
