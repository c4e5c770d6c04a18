#include "radiosity/hierarchy.h"
#include "radiosity/face_clusters.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace radiosity {

namespace {

Vec3 elementCentroid(const Node& e) {
    if (e.vertexCount == 3) return (e.v[0] + e.v[1] + e.v[2]) / 3.0;
    // Area-weighted centroid of the two fan triangles (exact for any convex quad).
    const double a1 = glm::length(glm::cross(e.v[1] - e.v[0], e.v[2] - e.v[0]));
    const double a2 = glm::length(glm::cross(e.v[2] - e.v[0], e.v[3] - e.v[0]));
    const double w = a1 + a2;
    if (!(w > 0)) return 0.25 * (e.v[0] + e.v[1] + e.v[2] + e.v[3]);
    return (a1 * (e.v[0] + e.v[1] + e.v[2]) + a2 * (e.v[0] + e.v[2] + e.v[3])) / (3.0 * w);
}

double elementArea(const Node& e) {
    double a = 0.5 * glm::length(glm::cross(e.v[1] - e.v[0], e.v[2] - e.v[0]));
    if (e.vertexCount == 4) a += 0.5 * glm::length(glm::cross(e.v[2] - e.v[0], e.v[3] - e.v[0]));
    return a;
}

void finishGeometry(Node& e) {
    e.bounds = Bounds3{};
    for (int i = 0; i < e.vertexCount; ++i) e.bounds.extend(e.v[i]);
    e.area = elementArea(e);
    e.centre = elementCentroid(e);
    e.radius = 0;
    for (int i = 0; i < e.vertexCount; ++i)
        e.radius = std::max(e.radius, glm::length(e.v[i] - e.centre));
}

/// An element's second moment of orientation, A n n^T (ClusterFields::normalMoment).
std::array<double, 6> elementMoment(const Node& e) {
    const Vec3& n = e.normal;
    return {e.area * n.x * n.x, e.area * n.y * n.y, e.area * n.z * n.z,
            e.area * n.x * n.y, e.area * n.x * n.z, e.area * n.y * n.z};
}

/// A cluster's box, area, orientation moments and bounding sphere from its children.
void aggregateChildren(std::vector<Node>& nodes, std::vector<ClusterFields>& fields, int node) {
    Node& c = nodes[node];
    ClusterFields& cf = fields[c.clusterSlot];
    c.bounds = Bounds3{};
    c.area = 0;
    cf.vectorArea = Vec3{0, 0, 0};
    cf.normalMoment = {};
    for (int k = 0; k < c.childCount; ++k) {
        const Node& ch = nodes[c.firstChild + k];
        c.bounds.extend(ch.bounds);
        c.area += ch.area;
        const bool cluster = ch.isCluster();
        cf.vectorArea += cluster ? fields[ch.clusterSlot].vectorArea : ch.area * ch.normal;
        const auto m = cluster ? fields[ch.clusterSlot].normalMoment : elementMoment(ch);
        for (int i = 0; i < 6; ++i) cf.normalMoment[i] += m[i];
    }
    c.centre = c.bounds.empty() ? Vec3{0, 0, 0} : c.bounds.centre();
    c.radius = c.bounds.empty() ? 0 : 0.5 * glm::length(c.bounds.diagonal());
    // Principal frame: eigenvectors of sum A n n^T (symmetric, so orthonormal).
    const auto& m = cf.normalMoment;
    Eigen::Matrix3d M;
    M << m[0], m[3], m[4], m[3], m[1], m[5], m[4], m[5], m[2];
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(M);
    if (eig.info() == Eigen::Success && std::isfinite(eig.eigenvectors().sum())) {
        for (int a = 0; a < 3; ++a) {
            const auto col = eig.eigenvectors().col(a);
            cf.frame[a] = glm::normalize(Vec3{col(0), col(1), col(2)});
        }
    }
}

}  // namespace

double selfTransferBound(double coneAngle) {
    if (!(coneAngle < std::numbers::pi / 2)) return 1.0;  // no useful bound (nor for NaN)
    const double c =
        std::sin(std::max(coneAngle, 0.0)) + 2 * std::sin(std::max(coneAngle, 0.0) / 2);
    return std::min(1.0, c * c);
}

double Hierarchy::projectedArea(const Node& node, const Vec3& v) const {
    if (!node.isCluster()) return node.area * std::max(0.0, glm::dot(node.normal, v));
    const ClusterFields& f = clusterFields[node.clusterSlot];
    const auto& M = f.normalMoment;
    const double vMv = M[0] * v.x * v.x + M[1] * v.y * v.y + M[2] * v.z * v.z +
                       2 * (M[3] * v.x * v.y + M[4] * v.x * v.z + M[5] * v.y * v.z);
    const double absProjected = std::sqrt(std::max(0.0, node.area * vMv));
    const double facing = 0.5 * (absProjected + glm::dot(f.vectorArea, v));
    const Vec3 d = node.bounds.empty() ? Vec3{0, 0, 0} : node.bounds.diagonal();
    const double box =
        std::abs(v.x) * d.y * d.z + std::abs(v.y) * d.x * d.z + std::abs(v.z) * d.x * d.y;
    return std::clamp(facing, 0.0, box);
}

namespace {

/// Bilinear on a quad; for a triangle the area-preserving square-to-triangle map.
Vec3 pointOnCorners(const std::array<Vec3, 4>& c, int count, double u, double v) {
    if (count == 4)
        return (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
    const double su = std::sqrt(u);
    return (1 - su) * c[0] + su * (1 - v) * c[1] + su * v * c[2];
}

}  // namespace

Vec3 pointOnElement(const Node& e, double u, double v) {
    return pointOnCorners(e.v, e.vertexCount, u, v);
}

Vec3 pointOnPolygon(const Polygon& p, double u, double v) {
    // (Not through a Node: building one, with its irradiance bins and frame, for every
    // sample point was a sixth of a 200 k-triangle room's preparation.)
    return pointOnCorners(p.v, p.vertexCount, u, v);
}

Hierarchy::Hierarchy(const Scene& scene, int maxPolygonsPerCluster) {
    const int n = static_cast<int>(scene.polygons.size());
    polygonOrder.resize(n);
    std::iota(polygonOrder.begin(), polygonOrder.end(), 0);
    polygonRoot.assign(n, -1);
    polygonPatch.assign(n, -1);
    nodes.reserve(4 * n + 16);
    nodes.push_back(newCluster(-1, 0));
    const BuildInput in(scene.polygons, 0);
    buildOverPatches(kRoot, in, std::max(1, maxPolygonsPerCluster));

    areaPrefix.assign(n + 1, 0.0);
    for (int i = 0; i < n; ++i)
        areaPrefix[i + 1] = areaPrefix[i] + scene.polygons[polygonOrder[i]].area;
    orderSampleCorners(0, in);
    for (int i = 0; i < n; ++i) {
        Node& e = nodes[polygonRoot[i]];
        e.E = scene.emittance(i);
        e.emitting = e.E.maxComponent() > 0;
    }
    pullAverages(kRoot);
}

Hierarchy::BuildInput::BuildInput(std::span<const Polygon> input, int first)
    : polygons(input), centroids(input.size()), base(first) {
    for (size_t i = 0; i < polygons.size(); ++i) centroids[i] = polygons[i].centroid();
}

namespace {

/// The clusters buildCluster() makes over `count` polygons, the first included: halved
/// until at most `maxPerCluster` are left.
size_t clustersOver(int count, int maxPerCluster) {
    if (count <= maxPerCluster) return 1;
    return 1 + clustersOver(count / 2, maxPerCluster) +
           clustersOver(count - count / 2, maxPerCluster);
}

}  // namespace

void Hierarchy::buildOverPatches(int node, const BuildInput& in, int maxPerCluster) {
    // The face clusters (face_clusters.h) are the units of the spatial split above them: a
    // patch is never cut by it, so every cluster below a patch's node is nearly planar.
    const std::span<const Polygon> polygons = in.polygons;
    const FaceClusterForest forest = buildFaceClusters(polygons);
    PatchSet set;
    set.centroid.reserve(forest.roots.size());
    std::vector<int> members;
    for (int root : forest.roots) {
        members.clear();
        forest.polygonsUnder(root, members);
        Vec3 c{0, 0, 0};
        double area = 0;
        for (int m : members) {
            const Polygon& p = polygons[static_cast<size_t>(m)];
            c += p.area * p.centroid();
            area += p.area;
        }
        set.start.push_back(static_cast<int>(set.polygons.size()));
        for (int m : members) set.polygons.push_back(in.base + m);
        set.centroid.push_back(area > 0 ? c / area
                                        : polygons[static_cast<size_t>(members[0])].centroid());
    }
    set.start.push_back(static_cast<int>(set.polygons.size()));
    set.order.resize(set.centroid.size());
    std::iota(set.order.begin(), set.order.end(), 0);
    // The clusters the build makes, at most: the patch level's inner nodes (fewer than the
    // patches) and, below them, what each patch would make on its own (patches grouped in
    // one cluster make fewer). Reserved before the build, so that the fields (a third of a
    // GB on a 1.6 M-face model) are not copied at each doubling nor left with its slack. An
    // object attached later grows them as push_back would, by doubling: the next ones then
    // find room.
    size_t bound = set.order.size();
    for (size_t k = 0; k < set.order.size(); ++k)
        bound += clustersOver(set.size(static_cast<int>(k)), maxPerCluster);
    if (const size_t need = clusterFields.size() + bound; need > clusterFields.capacity())
        clusterFields.reserve(std::max(need, 2 * clusterFields.size()));
    buildPatchLevel(node, set, 0, static_cast<int>(set.order.size()), in.base, maxPerCluster, in);
}

void Hierarchy::buildPatchLevel(int node, PatchSet& set, int pb, int pe, int begin,
                                int maxPerCluster, const BuildInput& in) {
    int count = 0;
    for (int i = pb; i < pe; ++i) count += set.size(set.order[i]);
    if (pe - pb == 1 || count <= maxPerCluster) {
        // One patch (split by position within it, all of it nearly planar), or few
        // polygons: laid out in patch order, then the polygon-level split.
        int at = begin;
        for (int i = pb; i < pe; ++i)
            for (int k = set.start[set.order[i]]; k < set.start[set.order[i] + 1]; ++k)
                polygonOrder[at++] = set.polygons[k];
        if (pe - pb == 1 && count > 1)
            for (int i = begin; i < at; ++i) polygonPatch[polygonOrder[i]] = node;
        buildCluster(node, begin, begin + count, maxPerCluster, in);
        return;
    }
    // Median split of the patches' centroids along the longest axis of their bounds.
    Bounds3 cb;
    for (int i = pb; i < pe; ++i) cb.extend(set.centroid[set.order[i]]);
    const int axis = cb.longestAxis();
    const int mid = pb + (pe - pb) / 2;
    std::nth_element(set.order.begin() + pb, set.order.begin() + mid, set.order.begin() + pe,
                     [&](int a, int b) {
                         if (set.centroid[a][axis] != set.centroid[b][axis])
                             return set.centroid[a][axis] < set.centroid[b][axis];
                         return a < b;  // deterministic order for ties
                     });
    int left = 0;
    for (int i = pb; i < mid; ++i) left += set.size(set.order[i]);
    nodes[node].polyBegin = begin;
    nodes[node].polyEnd = begin + count;
    const int first = addClusterChildren(node);
    buildPatchLevel(first, set, pb, mid, begin, maxPerCluster, in);
    buildPatchLevel(first + 1, set, mid, pe, begin + left, maxPerCluster, in);
    aggregateChildren(nodes, clusterFields, node);
    fitNormalCone(node, [&](int i) -> const Vec3& { return in[polygonOrder[i]].normal; });
}

int Hierarchy::addClusterChildren(int node) {
    const int first = static_cast<int>(nodes.size());
    nodes[node].firstChild = first;
    nodes[node].childCount = 2;
    for (int c = 0; c < 2; ++c) nodes.push_back(newCluster(node, nodes[node].level + 1));
    return first;
}

Node Hierarchy::newCluster(int parent, int level) {
    Node c;
    c.kind = NodeKind::cluster;
    c.parent = parent;
    c.level = level;
    c.clusterSlot = static_cast<int>(clusterFields.size());
    clusterFields.emplace_back();
    return c;
}

void Hierarchy::buildCluster(int node, int begin, int end, int maxPerCluster,
                             const BuildInput& in) {
    nodes[node].polyBegin = begin;
    nodes[node].polyEnd = end;
    const int count = end - begin;
    if (count <= maxPerCluster) {
        // Leaf cluster: its children are the root elements of its polygons.
        const int first = static_cast<int>(nodes.size());
        nodes[node].firstChild = first;
        nodes[node].childCount = count;
        const int level = nodes[node].level + 1;
        for (int i = begin; i < end; ++i) {
            const int p = polygonOrder[i];
            Node e;
            initElement(e, in[p], p);
            e.parent = node;
            e.level = level;
            polygonRoot[p] = static_cast<int>(nodes.size());
            nodes.push_back(e);
        }
    } else {
        // Median split of the centroids along the longest axis of their bounds.
        Bounds3 cb;
        const auto at = [&](int p) -> const Vec3& { return in.centroids[p - in.base]; };
        for (int i = begin; i < end; ++i) cb.extend(at(polygonOrder[i]));
        const int axis = cb.longestAxis();
        const int mid = begin + count / 2;
        std::nth_element(polygonOrder.begin() + begin, polygonOrder.begin() + mid,
                         polygonOrder.begin() + end, [&](int a, int b) {
                             if (at(a)[axis] != at(b)[axis]) return at(a)[axis] < at(b)[axis];
                             return a < b;  // deterministic order for ties
                         });
        const int first = addClusterChildren(node);
        buildCluster(first, begin, mid, maxPerCluster, in);
        buildCluster(first + 1, mid, end, maxPerCluster, in);
    }
    aggregateChildren(nodes, clusterFields, node);
    fitNormalCone(node, [&](int i) -> const Vec3& { return in[polygonOrder[i]].normal; });
}

template <class NormalAt>
void Hierarchy::fitNormalCone(int cluster, const NormalAt& normalAt) {
    // About the mean normal, as wide as its farthest polygon normal (pi when the normals
    // cancel out, as in a closed box's cluster).
    const Node& c = nodes[cluster];
    ClusterFields& f = clusterFields[c.clusterSlot];
    const double va = glm::length(f.vectorArea);
    f.coneAxis = va > 0 ? f.vectorArea / va : Vec3{0, 0, 1};
    double minCos = va > 0 ? 1.0 : -1.0;
    for (int i = c.polyBegin; i < c.polyEnd && minCos > -1; ++i)
        minCos = std::min(minCos, glm::dot(f.coneAxis, normalAt(i)));
    f.coneAngle = std::acos(std::clamp(minCos, -1.0, 1.0));
}

void Hierarchy::initElement(Node& e, const Polygon& p, int polygonIndex) {
    e.kind = NodeKind::element;
    e.polygon = polygonIndex;
    e.v = p.v;
    e.vertexCount = p.vertexCount;
    e.normal = p.normal;
    e.rho = p.rho;
    finishGeometry(e);
}

bool Hierarchy::unsubdivide(int node) {
    Node& n = nodes[node];
    if (n.childCount != 4 || n.firstChild + 4 != static_cast<int>(nodes.size())) return false;
    for (int k = 0; k < 4; ++k)
        if (!nodes[n.firstChild + k].isLeaf()) return false;
    nodes.resize(nodes.size() - 4);
    n.firstChild = -1;
    n.childCount = 0;
    return true;
}

void Hierarchy::truncateElements(size_t count) {
    if (nodes.size() > count) nodes.resize(count);
    for (Node& n : nodes)
        if (n.childCount > 0 && static_cast<size_t>(n.firstChild) >= count) {
            n.firstChild = -1;
            n.childCount = 0;
        }
}

bool Hierarchy::subdivide(int node) {
    if (nodes[node].isCluster() || !nodes[node].isLeaf()) return false;
    const Node parent = nodes[node];  // copy: push_back below may reallocate
    const int vc = parent.vertexCount;
    const auto corners = childCorners(parent.v, vc);
    const int first = static_cast<int>(nodes.size());
    for (int k = 0; k < 4; ++k) {
        Node child;
        child.kind = NodeKind::element;
        child.parent = node;
        child.level = parent.level + 1;
        child.polygon = parent.polygon;
        child.v = corners[k];
        child.vertexCount = vc;
        child.normal = parent.normal;
        child.rho = parent.rho;
        child.E = parent.E;
        child.B = parent.B;
        child.emitting = parent.emitting;
        child.gatherScale = parent.gatherScale;
        child.sendScale = parent.sendScale;
        child.lightCorrection = parent.lightCorrection;
        child.Hx = parent.Hx;  // until measured on the child (updateDirectIrradiance)
        child.Bsent = parent.Bsent;
        finishGeometry(child);
        nodes.push_back(child);
    }
    nodes[node].firstChild = first;
    nodes[node].childCount = 4;
    return true;
}

int Hierarchy::attachObject(std::span<const Polygon> polygons, int firstPolygon,
                            std::span<const Rgb> emittance, int maxPolygonsPerCluster,
                            int* oldRoot) {
    if (polygons.empty()) throw std::invalid_argument("attachObject: no polygon");
    if (firstPolygon != static_cast<int>(polygonOrder.size()) ||
        emittance.size() != polygons.size())
        throw std::invalid_argument("attachObject: polygons must follow the existing ones");
    Attached rec;
    rec.root = nodes[kRoot];
    rec.rootFields = clusterFields[nodes[kRoot].clusterSlot];
    rec.nodes = nodes.size();
    rec.polygons = polygonOrder.size();
    rec.clusters = clusterFields.size();
    const int n0 = static_cast<int>(nodes.size());
    // The old root's copy takes its children; every node below it is one level deeper.
    for (Node& n : nodes) ++n.level;
    Node copy = nodes[kRoot];
    copy.parent = kRoot;
    copy.clusterSlot = static_cast<int>(clusterFields.size());
    clusterFields.push_back(rec.rootFields);
    nodes.push_back(copy);
    for (int k = 0; k < copy.childCount; ++k) nodes[copy.firstChild + k].parent = n0;
    nodes.push_back(newCluster(kRoot, 1));

    const int begin = static_cast<int>(polygonOrder.size());
    const int total = firstPolygon + static_cast<int>(polygons.size());
    for (size_t i = 0; i < polygons.size(); ++i)
        polygonOrder.push_back(firstPolygon + static_cast<int>(i));
    polygonRoot.resize(total, -1);
    polygonPatch.resize(total, -1);
    const BuildInput in(polygons, firstPolygon);
    buildOverPatches(n0 + 1, in, std::max(1, maxPolygonsPerCluster));
    areaPrefix.resize(total + 1);
    for (int i = begin; i < total; ++i)
        areaPrefix[i + 1] = areaPrefix[i] + in[polygonOrder[i]].area;
    orderSampleCorners(static_cast<size_t>(begin), in);
    for (size_t i = 0; i < polygons.size(); ++i) {
        Node& e = nodes[polygonRoot[firstPolygon + i]];
        e.E = emittance[i];
        e.emitting = e.E.maxComponent() > 0;
    }
    pullAverages(n0 + 1);

    Node& root = nodes[kRoot];
    root.firstChild = n0;
    root.childCount = 2;
    root.polyBegin = 0;
    root.polyEnd = total;
    aggregateChildren(nodes, clusterFields, kRoot);
    // The root's cone spans the scene's polygons too, which only ordered_ holds here.
    fitNormalCone(kRoot,
                  [&](int i) -> const Vec3& { return ordered_[static_cast<size_t>(i)].normal; });
    root.level = 0;
    // The root's averages, from its two children only (the rest is unchanged).
    const double a0 = nodes[n0].area, a1 = nodes[n0 + 1].area;
    const double inv = root.area > 0 ? 1.0 / root.area : 0.0;  // guard: no area at all
    const Node& c0 = nodes[n0];
    const Node& c1 = nodes[n0 + 1];
    root.B = (c0.B * a0 + c1.B * a1) * inv;
    root.Bsent = (c0.Bsent * a0 + c1.Bsent * a1) * inv;
    root.rho = (c0.rho * a0 + c1.rho * a1) * inv;
    root.E = (c0.E * a0 + c1.E * a1) * inv;
    root.emitting = c0.emitting || c1.emitting;
    attached_.push_back(rec);
    if (oldRoot) *oldRoot = n0;
    return n0 + 1;
}

void Hierarchy::detachLastObject() {
    if (attached_.empty()) throw std::logic_error("detachLastObject: no object attached");
    const Attached rec = attached_.back();
    attached_.pop_back();
    nodes.resize(rec.nodes);
    nodes[kRoot] = rec.root;
    for (int k = 0; k < rec.root.childCount; ++k) nodes[rec.root.firstChild + k].parent = kRoot;
    for (Node& n : nodes) --n.level;
    nodes[kRoot].level = 0;  // it was not raised: restore its saved level
    clusterFields.resize(rec.clusters);
    clusterFields[nodes[kRoot].clusterSlot] = rec.rootFields;
    polygonOrder.resize(rec.polygons);
    polygonRoot.resize(rec.polygons);
    polygonPatch.resize(rec.polygons);
    areaPrefix.resize(rec.polygons + 1);
    ordered_.resize(rec.polygons);
}

void Hierarchy::orderSampleCorners(size_t from, const BuildInput& in) {
    ordered_.resize(from);
    ordered_.reserve(polygonOrder.size());
    for (size_t i = from; i < polygonOrder.size(); ++i) {
        const Polygon& p = in[polygonOrder[i]];
        ordered_.push_back({p.v, p.normal, p.vertexCount});
    }
}

void Hierarchy::updateEmittance(const Scene& scene) {
    for (Node& n : nodes) {
        if (n.isCluster()) continue;
        n.E = scene.emittance(n.polygon);
        n.emitting = n.E.maxComponent() > 0;
    }
    pullAverages(kRoot);
}

void Hierarchy::clustersAndRoots(std::vector<int>& clusters, std::vector<int>& roots) const {
    clusters.clear();
    roots.clear();
    std::vector<int> stack{kRoot};
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        const Node& c = nodes[n];
        if (!c.isCluster()) {
            roots.push_back(n);
            continue;
        }
        clusters.push_back(n);
        for (int k = 0; k < c.childCount; ++k) stack.push_back(c.firstChild + k);
    }
}

Vec3 Hierarchy::samplePoint(int node, double u, double v, double w, Vec3* normal,
                            int* order) const {
    const Node& n = nodes[node];
    if (!n.isCluster()) {
        if (normal) *normal = n.normal;
        if (order) *order = -1;
        return pointOnElement(n, u, v);
    }
    // Choose a polygon of the cluster by area (binary search in the prefix sums).
    const double a0 = areaPrefix[n.polyBegin], a1 = areaPrefix[n.polyEnd];
    const double target = a0 + w * (a1 - a0);
    auto it = std::upper_bound(areaPrefix.begin() + n.polyBegin + 1,
                               areaPrefix.begin() + n.polyEnd + 1, target);
    int idx = static_cast<int>(it - areaPrefix.begin()) - 1;
    idx = std::clamp(idx, n.polyBegin, n.polyEnd - 1);
    const SampleCorners& p = ordered_[idx];
    if (normal) *normal = p.normal;
    if (order) *order = idx;
    return pointOnCorners(p.v, p.vertexCount, u, v);
}

int Hierarchy::narrowestCovering(int node, int lo, int hi) const {
    for (;;) {
        const Node& n = nodes[node];
        if (!n.isCluster()) return node;
        int next = -1;
        for (int k = 0; k < n.childCount && next < 0; ++k) {
            const int c = n.firstChild + k;
            const Node& child = nodes[c];
            const bool covers =
                child.isCluster()
                    ? child.polyBegin <= lo && hi < child.polyEnd
                    : lo == hi && polygonOrder[static_cast<size_t>(lo)] == child.polygon;
            if (covers) next = c;
        }
        if (next < 0) return node;
        node = next;
    }
}

std::array<std::array<Vec3, 4>, 4> childCorners(const std::array<Vec3, 4>& v, int count) {
    const Vec3 m01 = 0.5 * (v[0] + v[1]), m12 = 0.5 * (v[1] + v[2]);
    if (count == 4) {
        const Vec3 m23 = 0.5 * (v[2] + v[3]), m30 = 0.5 * (v[3] + v[0]);
        const Vec3 c = 0.25 * (v[0] + v[1] + v[2] + v[3]);
        return {
            {{v[0], m01, c, m30}, {m01, v[1], m12, c}, {c, m12, v[2], m23}, {m30, c, m23, v[3]}}};
    }
    const Vec3 m20 = 0.5 * (v[2] + v[0]);
    return {
        {{v[0], m01, m20, {}}, {m01, v[1], m12, {}}, {m20, m12, v[2], {}}, {m12, m20, m01, {}}}};
}

bool elementContains(const Node& e, const Vec3& x, double tol) {
    for (int i = 0; i < e.vertexCount; ++i) {
        const Vec3& a = e.v[i];
        const Vec3& b = e.v[(i + 1) % e.vertexCount];
        if (glm::dot(glm::cross(b - a, x - a), e.normal) < -tol * glm::length(b - a)) return false;
    }
    return true;
}

std::vector<int> Hierarchy::edgeNeighbours(int leaf) const {
    std::vector<int> out;
    const Node& e = nodes[leaf];
    const Node& root = nodes[polygonRoot[e.polygon]];
    const double step = 1e-4 * e.radius;  // well inside any neighbour, far above rounding
    for (int i = 0; i < e.vertexCount; ++i) {
        const Vec3& a = e.v[i];
        const Vec3& b = e.v[(i + 1) % e.vertexCount];
        const Vec3 edge = b - a;
        const double len = glm::length(edge);
        if (!(len > 0)) continue;  // degenerate edge
        // Counter-clockwise corners: edge x normal points out of the element.
        const Vec3 out_dir = glm::cross(edge, e.normal) * (1.0 / len);
        for (double t : {0.25, 0.5, 0.75}) {
            const Vec3 x = a + t * edge + step * out_dir;
            if (!elementContains(root, x, 0.0)) continue;  // across the polygon's boundary
            const int n = locateLeaf(e.polygon, x);
            if (n != leaf && std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
        }
    }
    return out;
}

namespace {

// Which side of the line a->b, in the element's plane, x lies on (> 0: left, counter-clockwise
// about the normal n).
double side(const Vec3& a, const Vec3& b, const Vec3& x, const Vec3& n) {
    return glm::dot(glm::cross(b - a, x - a), n);
}

// The child of an element cut by subdivide() (childCorners) that holds x, from the parent's
// corners alone: a quad's children are the four parts cut by the lines through opposite edge
// midpoints (both pass through the centroid, the midpoint of either pair); a triangle's are
// its three corner triangles, each cut off by the line through its two edge midpoints, and the
// middle one. Points on a cut line go to the first side tested; points outside the element
// (rounding) go to the part next to them, as they would by the nearest centroid.
int childHolding(const Node& e, const Vec3& x) {
    const auto& v = e.v;
    const Vec3& n = e.normal;
    const Vec3 m01 = 0.5 * (v[0] + v[1]), m12 = 0.5 * (v[1] + v[2]);
    if (e.vertexCount == 4) {
        const Vec3 m23 = 0.5 * (v[2] + v[3]), m30 = 0.5 * (v[3] + v[0]);
        const bool top = side(m30, m12, x, n) >= 0;   // towards v2 and v3
        const bool left = side(m01, m23, x, n) >= 0;  // towards v3 and v0
        return top ? (left ? 3 : 2) : (left ? 0 : 1);
    }
    const Vec3 m20 = 0.5 * (v[2] + v[0]);
    // The middle triangle (m12, m20, m01) lies left of each of its edges; a corner's part is
    // right of the middle edge facing it.
    if (side(m20, m01, x, n) < 0) return 0;
    if (side(m01, m12, x, n) < 0) return 1;
    if (side(m12, m20, x, n) < 0) return 2;
    return 3;
}

}  // namespace

int Hierarchy::locateLeaf(int polygon, const Vec3& x) const {
    return locateLeafBelow(polygonRoot[polygon], x);
}

int Hierarchy::locateLeafBelow(int node, const Vec3& x) const {
    while (!nodes[node].isLeaf()) {
        const Node& n = nodes[node];
        if (n.childCount == 4 && (n.vertexCount == 3 || n.vertexCount == 4)) {
            // Every element is cut by subdivide(): the child from the parent's cut lines,
            // without reading the children (this runs once per ray of every gather).
            node = n.firstChild + childHolding(n, x);
            continue;
        }
        int best = -1;
        double bestDist = 1e300;
        for (int k = 0; k < n.childCount; ++k) {
            const Node& c = nodes[n.firstChild + k];
            if (elementContains(c, x, 1e-9)) {
                best = n.firstChild + k;
                break;
            }
            // Numerical fallback: the child whose centroid is nearest.
            const double d = glm::length(c.centre - x);
            if (d < bestDist) {
                bestDist = d;
                best = n.firstChild + k;
            }
        }
        node = best;
    }
    return node;
}

void Hierarchy::pullAverages(int node) {
    Node& n = nodes[node];
    if (n.isLeaf()) return;
    Rgb B, Bsent, rho, E;
    double area = 0;
    bool emitting = false;
    for (int k = 0; k < n.childCount; ++k) {
        const int c = n.firstChild + k;
        pullAverages(c);
        const Node& ch = nodes[c];
        B += ch.B * ch.area;
        Bsent += ch.Bsent * ch.area;
        rho += ch.rho * ch.area;
        E += ch.E * ch.area;
        area += ch.area;
        emitting = emitting || ch.emitting;
    }
    Node& m = nodes[node];  // re-fetch: recursion does not reallocate, but be explicit
    const double inv = area > 0 ? 1.0 / area : 0.0;  // guard: a cluster of no area
    m.B = B * inv;
    m.Bsent = Bsent * inv;
    if (m.isCluster()) {
        m.rho = rho * inv;
        m.E = E * inv;
    }
    m.emitting = emitting;
}

int Hierarchy::faceClusterCount() const {
    std::vector<int> patches;
    int own = 0;
    for (int p : polygonPatch) {
        if (p < 0)
            ++own;
        else
            patches.push_back(p);
    }
    std::sort(patches.begin(), patches.end());
    return own + static_cast<int>(std::unique(patches.begin(), patches.end()) - patches.begin());
}

int Hierarchy::leafCount() const {
    int count = 0;
    for (const Node& n : nodes)
        if (!n.isCluster() && n.isLeaf()) ++count;
    return count;
}

}  // namespace radiosity
