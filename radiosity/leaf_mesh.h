// LeafMesh: the distinct corners of the leaf elements of every input polygon, so that a
// quantity known at the corners can be interpolated smoothly over the surfaces.
//
// The hierarchical solution is one constant per leaf. Loscos, Drettakis & Robert 2000
// (§4.5, §5.3) display B and D at the leaf vertices, interpolated across each leaf by the
// graphics hardware (Gouraud); the same smooth reading is the cheapest one that does not
// draw the element grid. A corner shared by neighbouring leaves of one polygon is one vertex:
// subdivision computes a shared edge midpoint with the same floating-point expression on
// both sides, so equal corners are bit-identical and are matched exactly. Neighbouring
// polygons whose normals are within 25 degrees (kSmoothCos) share their common corners
// too: a wall that a reconstruction cut into triangles (or a gently curved surface) is
// interpolated as one surface, and the relit photo does not show the triangulation; at a
// sharper edge (a box's 90 degrees) each side keeps its own vertex. A shared vertex's
// `polygon` is the first one that made it. Where a large
// leaf meets the edges of smaller ones (a T-vertex), the large leaf interpolates between its
// own corners only; the small crack this leaves is the one the paper's display has too.
//
// A leaf may also be displayed finer than it is solved: split s times, it is cut as
// Hierarchy::subdivide would cut it, into 4^s pieces, and the pieces' corners are vertices
// too. A leaf's value is one constant, but the light at its vertices (direct light with its
// shadow rays, and the final gather; relight/pipeline/vertex_lighting.h) is measured at each point,
// so more vertices draw shadows and gradients that the leaf's single value cannot. A
// triangle has half as many corners per element as a quad (a mesh of n triangles has about
// n/2 vertices), so a reconstruction's triangles are drawn as coarsely as quads of twice
// their size unless they are split. The pieces' corners are made with Hierarchy::subdivide's
// expressions, so they are bit-identical to the corners of a neighbour that was subdivided
// along the same edge, and a split leaf meets finer neighbours without a T-vertex.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "radiosity/hierarchy.h"
#include "radiosity/rgb.h"

namespace radiosity {

class LeafMesh {
  public:
    /// Cosine of the largest angle between the normals of two polygons whose common
    /// corners are one vertex.
    static constexpr double kSmoothCos = 0.9063077870366499;  // cos(25 degrees)

    /// How many times a leaf's display is split (0: its corners only; at most kMaxSplits).
    using SplitRule = std::function<int(int leaf)>;
    static constexpr int kMaxSplits = 4;

    /// Collects the leaf corners of every polygon of `h` (the hierarchy as it stands), and
    /// the corners of the display pieces of the leaves that `split` splits.
    explicit LeafMesh(const Hierarchy& h, const SplitRule& split = {});
    /// The same for the leaves whose node id is at least `firstNode` and whose polygon is
    /// at least `firstPolygon` only (the objects inserted after the scene's hierarchy was
    /// built, Hierarchy::attachObject, without the scene's leaves split since).
    LeafMesh(const Hierarchy& h, int firstNode, const SplitRule& split = {}, int firstPolygon = 0);

    struct Vertex {
        Vec3 position;  ///< metres
        int polygon;    ///< the input polygon it lies on
    };
    const Hierarchy& hierarchy() const { return h_; }
    const std::vector<Vertex>& vertices() const { return vertices_; }
    /// Vertex ids of a leaf element's corners (in its corner order; 3 or 4 are valid).
    const std::array<int, 4>& corners(int leaf) const { return corners_[leaf]; }

    /// Interpolation weights of point x (on `leaf`'s plane) over the leaf's corners:
    /// barycentric on a triangle, inverse bilinear on a quad. Weights sum to 1 and are
    /// clamped to the leaf (a point just outside gets its nearest boundary's weights).
    std::array<double, 4> weights(int leaf, const Vec3& x) const;

    /// The vertices and weights that interpolate a value at x on `leaf`: the corners of the
    /// display piece that holds x, with linear (triangle) or bilinear (quad) weights over
    /// the piece; on an unsplit leaf, its corners and `weights`. Weights sum to 1.
    struct Stencil {
        std::array<int, 4> vertex{-1, -1, -1, -1};
        std::array<double, 4> weight{0, 0, 0, 0};
        int count = 0;
    };
    Stencil stencil(int leaf, const Vec3& x) const;
    /// Every vertex of a leaf: its corners, or all its display pieces' corners.
    std::vector<int> vertexIds(int leaf) const;
    /// How many times the leaf's display is split.
    int splits(int leaf) const { return splits_[leaf]; }

    /// The value at x on `polygon` interpolated from per-vertex `values`.
    Rgb interpolate(const std::vector<Rgb>& values, int polygon, const Vec3& x) const;

    /// Per-vertex values by the Gouraud rule: the area-weighted mean of the leaf values
    /// `leafValue(node)` over the leaves that have the vertex as a corner (or as a corner of
    /// one of their display pieces).
    std::vector<Rgb> averageOfLeaves(const std::function<Rgb(int leaf)>& leafValue) const;

    /// A point at vertex v moved a tiny step (1e-4 of the leaf's radius) towards the centre
    /// of one leaf that owns it: inside the polygon, so that rays and point location from
    /// it never start exactly on a polygon edge.
    Vec3 insidePoint(int v) const;

  private:
    const Hierarchy& h_;
    std::vector<Vertex> vertices_;
    std::vector<std::array<int, 4>> corners_;  // by node id; -1 where not a leaf element
    std::vector<uint8_t> splits_;              // by node id
    // By node id: where a split leaf's grid of vertex ids starts in grid_ (-1: not split).
    // A quad split s times has (n+1)^2 grid points, n = 2^s, at (i, j): i along v0->v1, j
    // along v0->v3; a triangle has (n+1)(n+2)/2, at integer barycentric coordinates (i, j)
    // of v1 and v2 (gridIndex).
    std::vector<int> gridStart_;
    std::vector<int> grid_;
    std::vector<int> ownerLeaf_;  // by vertex: one leaf having it as a corner
};

}  // namespace radiosity
