// Hierarchy: the element quadtrees of the input polygons under a cluster hierarchy,
// stored as one flat array of nodes indexed by node id.
//
// Hanrahan, Salzman & Aupperle 1991 (elements); Sillion 1995 and Smits, Arvo & Greenberg
// 1994 (clusters). The root cluster (node 0) holds the whole scene. A cluster covers a
// contiguous range of `polygonOrder`; its children are clusters, or, at the bottom, the
// root elements of its polygons. An element is a triangle or a planar convex quad on one
// input polygon; subdividing it makes 4 children (midpoint split of a quad on its
// bilinear parameterisation; 4-way midpoint split of a triangle), all with the polygon's
// orientation. Children of a node are contiguous in `nodes`.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/directional_irradiance.h"
#include "radiosity/rgb.h"
#include "radiosity/scene.h"
#include "radiosity/vec.h"

namespace radiosity {

enum class NodeKind : uint8_t { cluster, element };

struct Node {
    NodeKind kind = NodeKind::element;
    int parent = -1;
    int firstChild = -1;             ///< index of the first child; children are contiguous
    int childCount = 0;              ///< 0 for a leaf element
    int level = 0;                   ///< depth below the root cluster
    int polygon = -1;                ///< element: its input polygon; cluster: -1
    int polyBegin = 0, polyEnd = 0;  ///< cluster: its range of Hierarchy::polygonOrder

    std::array<Vec3, 4> v{};  ///< element corners, counter-clockwise (metres)
    int vertexCount = 0;      ///< element: 3 or 4; cluster: 0
    /// Cluster: its index in Hierarchy::clusterFields (what only clusters have); -1 for an
    /// element.
    int clusterSlot = -1;
    Vec3 normal{0, 0, 1};  ///< element: unit front normal
    Vec3 centre{0, 0, 0};  ///< element: centroid; cluster: box centre (metres)
    double radius = 0;     ///< bounding-sphere radius about `centre` (metres)
    Bounds3 bounds;
    double area = 0;  ///< element: its area; cluster: total area of its polygons (m^2)

    Rgb rho;  ///< reflectance (cluster: area-weighted mean)
    Rgb E;    ///< emittance, radiosity units (cluster: area-weighted mean)
    Rgb B;    ///< radiosity, radiosity units (cluster: area-weighted mean of its contents)
    /// Element: irradiance gathered through its own links in the last gather from sources
    /// that reflect (Hd: from those that do not, the lamps' emitting faces).
    Rgb H, Hd;
    /// Leaf element: factor on what it gathers from sources that reflect, seen / G
    /// (HierarchicalSolver, "energy bound"); 1 until measured.
    double gatherScale = 1;
    /// Leaf element: the fraction of its cosine-weighted hemisphere in which it sees the
    /// front of a surface, measured by ray casting (-1 until measured), and the
    /// standard error of that measurement (0 when every ray or none saw one).
    double seen = -1, seenError = 0;
    bool emitting = false;  ///< an emitter with E > 0 lies in this node
    // The balance of sends, last: the fields above keep their offsets, which the solver's
    // hot loops were laid out against.
    /// What the node sends through its links: a leaf B sendScale, a cluster or inner
    /// element the area-weighted mean of its children's (HierarchicalSolver, "energy bound").
    Rgb Bsent;
    /// Leaf element: factor on what it sends through its links (the column balance of the
    /// energy bound); 1 until balanced, and for a face that does not reflect.
    double sendScale = 1;
    /// Leaf element: the link correction of real-shadow removal on its links from lights
    /// (HierarchicalSolver::scaleLightLinks; Loscos et al. 2000, Eq. (15)), 1 without one.
    /// Kept so that a link from a light that gets its visibility again (a dynamic update
    /// cut it) or is split to the children keeps the correction.
    double lightCorrection = 1;
    /// Leaf element: the direct irradiance of the lights that are not faces (the
    /// solver's emitters: sun, point lamps, sky; radiosity/emitter.h), the mean over the
    /// element with visibility (radiosity units). It enters B as the lamps' Hd does.
    Rgb Hx;
    /// Whether Hx was measured on this element (a child inherits its parent's until then).
    bool HxMeasured = false;

    bool isCluster() const { return kind == NodeKind::cluster; }
    bool isLeaf() const { return childCount == 0; }
};

/// What only a cluster has, kept beside the nodes (Hierarchy::clusterFields) rather than in
/// every Node: elements outnumber clusters, and these 320 bytes were more than a third of
/// each node (a 1.6 M-face model holds 2.4 M nodes). An element's orientation follows from
/// its normal and area (Hierarchy::coneAxis, coneAngle, projectedArea).
struct ClusterFields {
    /// Orientation of the cluster's surfaces, for projectedArea(): the vector area
    /// sum A_i n_i (m^2) and the second moment sum A_i n_i n_i^T (m^2; xx, yy, zz, xy, xz,
    /// yz) over its polygons.
    Vec3 vectorArea{0, 0, 0};
    std::array<double, 6> normalMoment{};
    /// Normal cone: every surface's front normal in the cluster lies within coneAngle
    /// (radians) of coneAxis (pi: no bound).
    Vec3 coneAxis{0, 0, 1};
    double coneAngle = 0;
    /// The cluster's principal frame of orientation, the eigenvectors of its normalMoment
    /// (rows: unit axes), in which its directional irradiance is binned.
    std::array<Vec3, 3> frame{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
    DirectionalIrradiance Hv;  ///< irradiance gathered through the cluster's own links
};

class Hierarchy {
  public:
    /// Builds the cluster hierarchy over `scene` and one root element per polygon: the
    /// polygons' face clusters (connected, nearly planar patches: face_clusters.h), split
    /// by their centroids (median along the longest axis), then each patch by its polygons'
    /// centroids, down to at most `maxPolygonsPerCluster` polygons per leaf cluster. Reflectance
    /// and emittance come from `scene`.
    explicit Hierarchy(const Scene& scene, int maxPolygonsPerCluster = 4);

    static constexpr int kRoot = 0;

    std::vector<Node> nodes;
    std::vector<int> polygonRoot;   ///< polygon index -> its root element node
    std::vector<int> polygonOrder;  ///< polygons in cluster order
    /// Polygon index -> the cluster node of its face cluster (a patch of at least two
    /// polygons, face_clusters.h), or -1 for a polygon that is a patch of its own. What is
    /// measured per surface rather than per polygon (the leaves' `seen`) is measured there.
    std::vector<int> polygonPatch;
    std::vector<double> areaPrefix;  ///< areaPrefix[i] = sum of areas of polygonOrder[0, i)
    /// One per cluster, at its Node::clusterSlot; slots follow the clusters' creation, so
    /// detachLastObject() drops the newest ones.
    std::vector<ClusterFields> clusterFields;

    /// A cluster's directional irradiance and frame (`cluster` must be a cluster).
    DirectionalIrradiance& Hv(const Node& cluster) { return clusterFields[cluster.clusterSlot].Hv; }
    const DirectionalIrradiance& Hv(const Node& cluster) const {
        return clusterFields[cluster.clusterSlot].Hv;
    }
    const std::array<Vec3, 3>& frame(const Node& cluster) const {
        return clusterFields[cluster.clusterSlot].frame;
    }
    /// Direction v (world) in the cluster's principal frame.
    Vec3 toFrame(const Node& cluster, const Vec3& v) const;
    /// Normal cone of a node: every surface's front normal in it lies within coneAngle
    /// (radians) of coneAxis (an element: its normal, angle 0).
    const Vec3& coneAxis(const Node& n) const {
        return n.isCluster() ? clusterFields[n.clusterSlot].coneAxis : n.normal;
    }
    double coneAngle(const Node& n) const {
        return n.isCluster() ? clusterFields[n.clusterSlot].coneAngle : 0.0;
    }
    /// Area of the node's surfaces facing direction v (unit), projected onto the plane
    /// perpendicular to v (m^2): the area a distant observer in direction v sees, without the
    /// surfaces' mutual occlusion. Exact for an element, A max(0, n.v). For a cluster:
    ///     sum A_i max(0, n_i.v) = 1/2 sum A_i |n_i.v| + 1/2 a.v     (a: vectorArea)
    /// and, by Cauchy-Schwarz, sum A_i |n_i.v| <= sqrt(A v^T M v) (M: normalMoment), exact
    /// when the surfaces are parallel (a face cluster) and 15 % high for a sphere. The result
    /// is at most the cross-section of the cluster's box in direction v, which no set of
    /// surfaces inside it can exceed as seen from outside (Smits, Arvo & Greenberg 1994).
    double projectedArea(const Node& node, const Vec3& v) const;

    /// Splits a leaf element into 4 children (returns false for clusters and non-leaves).
    bool subdivide(int node);
    /// Undoes subdivide(node) when its 4 children are the newest nodes and leaves
    /// (returns false otherwise, changing nothing).
    bool unsubdivide(int node);
    /// Drops the element nodes from `count` on (subdivisions made after a snapshot of
    /// `count` nodes) and makes leaves again of the nodes whose children they were.
    void truncateElements(size_t count);

    /// Dynamic objects (Drettakis & Sillion 1997; Loscos et al. 2000, §5.1): attaches
    /// `polygons`, whose Scene::polygons indices are firstPolygon, firstPolygon + 1, ... (the
    /// next free ones), as a new cluster under the root. The root's contents move to a new
    /// node (the old root's copy, returned in *oldRoot) so that the root has two contiguous
    /// children, that copy and the object's cluster; every other node keeps its id.
    /// Reflectance and emittance come from the polygons (E from `emittance`, one per
    /// polygon). Returns the object's cluster node.
    int attachObject(std::span<const Polygon> polygons, int firstPolygon,
                     std::span<const Rgb> emittance, int maxPolygonsPerCluster, int* oldRoot);
    /// Undoes the last attachObject(): the nodes from the old root's copy on go (also any
    /// made since, which must all lie under the object), and the root, polygon order and
    /// levels are as before, bit for bit. Throws std::logic_error with no object attached.
    void detachLastObject();
    /// Number of objects attached and not detached.
    int attachedObjects() const { return static_cast<int>(attached_.size()); }

    /// Re-reads emittance from `scene` (after a light edit) and updates `emitting` and the
    /// clusters' mean E.
    void updateEmittance(const Scene& scene);

    /// A point on the node's surfaces for uniform random numbers (u, v, w) in [0, 1):
    /// uniform by area on an element; for a cluster, a polygon is chosen with probability
    /// proportional to its area (w), then a point on it (u, v). `order`, when given, gets
    /// the chosen polygon's position in polygonOrder (-1 for an element).
    Vec3 samplePoint(int node, double u, double v, double w, Vec3* normal = nullptr,
                     int* order = nullptr) const;
    /// The deepest node under `node` (itself included) whose polygons include every
    /// polygon of polygonOrder[lo, hi] (positions within node's range): a cluster, or the
    /// root element of a single polygon.
    int narrowestCovering(int node, int lo, int hi) const;

    /// The leaf element of `polygon` that contains x (a point on the polygon).
    int locateLeaf(int polygon, const Vec3& x) const;
    /// The same below element `node` (a point on it).
    int locateLeafBelow(int node, const Vec3& x) const;

    /// The leaf elements of the same polygon that share part of an edge with leaf `leaf`.
    /// Found by probing just outside each edge at 1/4, 1/2 and 3/4 of its length: a leaf
    /// finds every neighbour at least as large as itself across each edge, and a smaller
    /// one finds it: the union over both sides is the full relation.
    std::vector<int> edgeNeighbours(int leaf) const;

    /// Pull: recomputes cluster/parent B, rho, E, area-weighted from the leaves.
    void pullAverages(int node);

    int leafCount() const;
    /// The face clusters (polygonPatch): patches of several polygons, and polygons of their own.
    int faceClusterCount() const;
    /// The clusters in top-down order (each after its parent) and the polygons' root
    /// elements (the element children of clusters), from a walk down from the root.
    void clustersAndRoots(std::vector<int>& clusters, std::vector<int>& roots) const;
    int clusterCount() const { return static_cast<int>(clusterFields.size()); }
    int elementCount() const { return static_cast<int>(nodes.size()) - clusterCount(); }

  private:
    /// The input polygons' face clusters (face_clusters.h), as runs of polygon indices, with
    /// their area-weighted centroids; `order` is the patches' order as the split leaves it.
    struct PatchSet {
        std::vector<int> polygons, start, order;
        std::vector<Vec3> centroid;
        int size(int patch) const { return start[patch + 1] - start[patch]; }
    };
    /// The polygons a build reads (Scene indices base, base + 1, ...), for the length of the
    /// build only: the hierarchy keeps no copy of them (the solver's Scene holds them, and
    /// after the build the hierarchy reads their corners from ordered_).
    struct BuildInput {
        std::span<const Polygon> polygons;
        std::vector<Vec3> centroids;  ///< by polygon index less `base`
        int base = 0;
        BuildInput(std::span<const Polygon> polygons, int base);
        const Polygon& operator[](int p) const { return polygons[static_cast<size_t>(p - base)]; }
    };
    /// Builds the subtree of `node` over in.polygons (Scene indices base, base + 1, ...,
    /// already in polygonOrder from position base): the polygons' face clusters, split by
    /// their centroids (median along the longest axis) down to one patch, or to at most
    /// `maxPerCluster` polygons; each patch then split by its polygons' centroids.
    void buildOverPatches(int node, const BuildInput& in, int maxPerCluster);
    void buildPatchLevel(int node, PatchSet& set, int pb, int pe, int begin, int maxPerCluster,
                         const BuildInput& in);
    /// Appends two empty cluster children to `node`; returns the first one's id.
    int addClusterChildren(int node);
    /// Median split of polygonOrder[begin, end) by centroid (in.centroids) down to leaf
    /// clusters of at most maxPerCluster root elements.
    void buildCluster(int node, int begin, int end, int maxPerCluster, const BuildInput& in);
    /// A cluster's normal cone from its polygons' normals (ClusterFields::coneAxis, coneAngle);
    /// normalAt(i): the normal of the polygon at polygonOrder[i].
    template <class NormalAt>
    void fitNormalCone(int cluster, const NormalAt& normalAt);
    void initElement(Node& e, const Polygon& p, int polygonIndex);
    /// A new cluster node (not yet in `nodes`) with its slot in clusterFields.
    Node newCluster(int parent, int level);
    /// What samplePoint reads of a polygon, in polygonOrder's order: a cluster's polygons
    /// lie together, and a sample reads one 128-byte record (not the polygon's index,
    /// then its whole record elsewhere: two cache misses per point on a large mesh).
    struct SampleCorners {
        std::array<Vec3, 4> v;
        Vec3 normal;
        int vertexCount;
    };
    std::vector<SampleCorners> ordered_;
    /// ordered_[from, end) from polygonOrder, whose polygons from `from` on are in.polygons.
    void orderSampleCorners(size_t from, const BuildInput& in);
    struct Attached {
        Node root;                 // the root before the attachment
        ClusterFields rootFields;  // and its cluster fields
        size_t nodes = 0, polygons = 0, clusters = 0;
    };
    std::vector<Attached> attached_;  // a stack: detachLastObject() pops
};

/// The largest share of a surface's emitted light that can land on the surface itself,
/// given the normal cone (half-angle t, radians) of its faces: min(1, (sin t + 2 sin(t/2))^2),
/// 0 for a plane (HierarchicalSolver's "self-interaction" says why; any t >= pi/2: 1).
double selfTransferBound(double coneAngle);

/// Whether a link's source reflects light: a cluster (the oracle splits any cluster that
/// holds an emitter off a link, so a cluster stands for reflecting surfaces), or an
/// element of non-zero reflectance. A lamp's face does not: its links carry direct light.
inline bool reflects(const Node& source) {
    return source.isCluster() || source.rho.maxComponent() > 0;
}

/// Direction v (world) in a principal frame (ClusterFields::frame).
inline Vec3 toFrame(const std::array<Vec3, 3>& frame, const Vec3& v) {
    return {glm::dot(frame[0], v), glm::dot(frame[1], v), glm::dot(frame[2], v)};
}

inline Vec3 Hierarchy::toFrame(const Node& cluster, const Vec3& v) const {
    return radiosity::toFrame(frame(cluster), v);
}

/// Whether point x (on the element's plane) lies in element e, edges included to within
/// tol x edge length.
bool elementContains(const Node& e, const Vec3& x, double tol);

/// Point on element `e` for (u, v) in [0, 1]^2: bilinear on a quad; for a triangle the
/// area-preserving square-to-triangle map (sqrt warp).
Vec3 pointOnElement(const Node& e, double u, double v);

/// The corners of the four children of an element with corners `v` (`count` 3 or 4), in
/// Hierarchy::subdivide's child order: a quad's (v0, m01, c, m30), (m01, v1, m12, c),
/// (c, m12, v2, m23), (m30, c, m23, v3); a triangle's (v0, m01, m20), (m01, v1, m12),
/// (m20, m12, v2) and the middle (m12, m20, m01), which keeps the parent's orientation.
/// Midpoints are 0.5 (a + b) and a quad's centre 0.25 (v0 + v1 + v2 + v3), so the
/// midpoint of a shared edge is bit-identical from both sides.
std::array<std::array<Vec3, 4>, 4> childCorners(const std::array<Vec3, 4>& v, int count);
/// Same for an input polygon.
Vec3 pointOnPolygon(const Polygon& p, double u, double v);

}  // namespace radiosity
