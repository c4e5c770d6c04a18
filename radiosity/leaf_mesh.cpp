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

// Index of grid point (i, j) of a leaf with `k` corners split into n x n (quad) or n^2
// (triangle) pieces; see LeafMesh::gridStart_.
int gridIndex(int k, int n, int i, int j) {
    return k == 4 ? j * (n + 1) + i : j * (n + 1) - j * (j - 1) / 2 + i;
}

int gridSize(int k, int n) {
    return k == 4 ? (n + 1) * (n + 1) : (n + 1) * (n + 2) / 2;
}

// A display piece: its corners' positions and integer grid coordinates.
struct Piece {
    std::array<Vec3, 4> v;
    std::array<std::array<int, 2>, 4> at;
};

// The four pieces of `p`, cut as Hierarchy::subdivide cuts an element (childCorners: the
// same points, bit for bit, and the same order), with their corners' grid coordinates.
std::array<Piece, 4> quarters(const Piece& p, int k) {
    const auto v = childCorners(p.v, k);
    const auto& a = p.at;
    auto mid = [](const std::array<int, 2>& x, const std::array<int, 2>& y) {
        return std::array<int, 2>{(x[0] + y[0]) / 2, (x[1] + y[1]) / 2};
    };
    const auto a01 = mid(a[0], a[1]), a12 = mid(a[1], a[2]);
    if (k == 4) {
        const auto a23 = mid(a[2], a[3]), a30 = mid(a[3], a[0]), ac = mid(a[0], a[2]);
        return {{{v[0], {a[0], a01, ac, a30}},
                 {v[1], {a01, a[1], a12, ac}},
                 {v[2], {ac, a12, a[2], a23}},
                 {v[3], {a30, ac, a23, a[3]}}}};
    }
    const auto a20 = mid(a[2], a[0]);
    return {{{v[0], {a[0], a01, a20, {}}},
             {v[1], {a01, a[1], a12, {}}},
             {v[2], {a20, a12, a[2], {}}},
             {v[3], {a12, a20, a01, {}}}}};
}

// The leaf itself as a piece, with its corners' grid coordinates for n = 2^splits.
Piece wholeLeaf(const Node& e, int n) {
    Piece p{e.v, {}};
    if (e.vertexCount == 4)
        p.at = {{{0, 0}, {n, 0}, {n, n}, {0, n}}};
    else
        p.at = {{{0, 0}, {n, 0}, {0, n}, {0, 0}}};
    return p;
}

}  // namespace

LeafMesh::LeafMesh(const Hierarchy& h, const SplitRule& split) : LeafMesh(h, 0, split) {}

LeafMesh::LeafMesh(const Hierarchy& h, int firstNode, const SplitRule& split, int firstPolygon)
    : h_(h), corners_(h.nodes.size()), splits_(h.nodes.size(), 0), gridStart_(h.nodes.size(), -1) {
    // The vertices at one position, each with the normal of the polygon that made it.
    std::unordered_map<CornerKey, std::vector<int>, CornerKeyHash> index;
    auto vertexAt = [&](const Vec3& p, size_t n) {
        const Node& e = h.nodes[n];
        // +0.0 folds -0.0 into 0.0 so that the bit patterns of equal corners agree.
        std::vector<int>& here = index[CornerKey{p.x + 0.0, p.y + 0.0, p.z + 0.0}];
        for (int v : here) {
            const Node& owner = h.nodes[ownerLeaf_[v]];
            if (owner.polygon == e.polygon || glm::dot(owner.normal, e.normal) >= kSmoothCos)
                return v;
        }
        const int id = static_cast<int>(vertices_.size());
        here.push_back(id);
        vertices_.push_back({p, e.polygon});
        ownerLeaf_.push_back(static_cast<int>(n));
        return id;
    };
    const size_t first = static_cast<size_t>(std::max(firstNode, 0));
    for (size_t n = 0; n < h.nodes.size(); ++n) {
        corners_[n] = {-1, -1, -1, -1};
        const Node& e = h.nodes[n];
        if (n < first || e.isCluster() || !e.isLeaf() || e.polygon < firstPolygon) continue;
        for (int i = 0; i < e.vertexCount; ++i) corners_[n][i] = vertexAt(e.v[i], n);
        const int s = split ? std::clamp(split(static_cast<int>(n)), 0, kMaxSplits) : 0;
        if (s == 0) continue;
        splits_[n] = static_cast<uint8_t>(s);
        const int k = e.vertexCount, side = 1 << s;
        gridStart_[n] = static_cast<int>(grid_.size());
        grid_.resize(grid_.size() + gridSize(k, side), -1);
        int* ids = grid_.data() + gridStart_[n];
        // Cut the leaf s times, recursively, and make a vertex of every piece's corners.
        auto cut = [&](auto&& self, const Piece& p, int depth) -> void {
            if (depth == s) {
                for (int c = 0; c < k; ++c) {
                    int& id = ids[gridIndex(k, side, p.at[c][0], p.at[c][1])];
                    if (id < 0) id = vertexAt(p.v[c], n);
                }
                return;
            }
            for (const Piece& q : quarters(p, k)) self(self, q, depth + 1);
        };
        cut(cut, wholeLeaf(e, side), 0);
    }
}

LeafMesh::Stencil LeafMesh::stencil(int leaf, const Vec3& x) const {
    const Node& e = h_.nodes[leaf];
    auto w = weights(leaf, x);
    Stencil st;
    st.count = e.vertexCount;
    const int s = splits_[leaf];
    if (s == 0) {
        for (int i = 0; i < st.count; ++i) {
            st.vertex[i] = corners_[leaf][i];
            st.weight[i] = w[i];
        }
        return st;
    }
    const int side = 1 << s;
    const int* ids = grid_.data() + gridStart_[leaf];
    if (e.vertexCount == 4) {
        // The bilinear (s, t) of `weights`; midpoint cuts of a bilinear patch are the
        // patch's own parameter lines, so the piece is cell (i, j) of the grid.
        const double u = (w[1] + w[2]) * side, t = (w[2] + w[3]) * side;
        const int i = std::clamp(static_cast<int>(u), 0, side - 1);
        const int j = std::clamp(static_cast<int>(t), 0, side - 1);
        const double a = std::clamp(u - i, 0.0, 1.0), b = std::clamp(t - j, 0.0, 1.0);
        st.vertex = {ids[gridIndex(4, side, i, j)], ids[gridIndex(4, side, i + 1, j)],
                     ids[gridIndex(4, side, i + 1, j + 1)], ids[gridIndex(4, side, i, j + 1)]};
        st.weight = {(1 - a) * (1 - b), a * (1 - b), a * b, (1 - a) * b};
        return st;
    }
    // A triangle: descend the cuts. A corner's piece holds the points whose barycentric
    // weight for that corner is at least 1/2, the middle piece the rest; on each piece the
    // weights are linear again (the maps below are the inverses of the midpoint cuts).
    Piece p = wholeLeaf(e, side);
    for (int depth = 0; depth < s; ++depth) {
        const auto q = quarters(p, 3);
        int c;
        if (w[0] >= 0.5) {
            c = 0;
            w = {2 * w[0] - 1, 2 * w[1], 2 * w[2], 0};
        } else if (w[1] >= 0.5) {
            c = 1;
            w = {2 * w[0], 2 * w[1] - 1, 2 * w[2], 0};  // piece (m01, v1, m12)
        } else if (w[2] >= 0.5) {
            c = 2;
            w = {2 * w[0], 2 * w[1], 2 * w[2] - 1, 0};  // piece (m20, m12, v2)
        } else {
            c = 3;
            w = {1 - 2 * w[0], 1 - 2 * w[1], 1 - 2 * w[2], 0};  // piece (m12, m20, m01)
        }
        // Rounding: keep the weights a partition of unity.
        double sum = 0;
        for (int i = 0; i < 3; ++i) sum += (w[i] = std::max(w[i], 0.0));
        for (int i = 0; i < 3; ++i) w[i] = sum > 0 ? w[i] / sum : 1.0 / 3;
        p = q[c];
    }
    for (int i = 0; i < 3; ++i) {
        st.vertex[i] = ids[gridIndex(3, side, p.at[i][0], p.at[i][1])];
        st.weight[i] = w[i];
    }
    return st;
}

std::vector<int> LeafMesh::vertexIds(int leaf) const {
    const Node& e = h_.nodes[leaf];
    if (splits_[leaf] == 0) {
        std::vector<int> ids;
        for (int v : corners_[leaf])
            if (v >= 0) ids.push_back(v);
        return ids;
    }
    const int* first = grid_.data() + gridStart_[leaf];
    return {first, first + gridSize(e.vertexCount, 1 << splits_[leaf])};
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
    const Stencil s = stencil(h_.locateLeaf(polygon, x), x);
    Rgb out;
    for (int i = 0; i < s.count; ++i) out += s.weight[i] * values[s.vertex[i]];
    return out;
}

std::vector<Rgb> LeafMesh::averageOfLeaves(const std::function<Rgb(int leaf)>& leafValue) const {
    std::vector<Rgb> sum(vertices_.size());
    std::vector<double> area(vertices_.size(), 0.0);
    for (size_t n = 0; n < corners_.size(); ++n) {
        if (corners_[n][0] < 0) continue;
        const Node& e = h_.nodes[n];
        const Rgb b = leafValue(static_cast<int>(n));
        for (int v : vertexIds(static_cast<int>(n))) {
            sum[v] += e.area * b;
            area[v] += e.area;
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
