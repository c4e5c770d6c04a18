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
#pragma once

#include <array>
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

    /// Collects the leaf corners of every polygon of `h` (the hierarchy as it stands).
    explicit LeafMesh(const Hierarchy& h);
    /// The same for the leaves whose node id is at least `firstNode` only (the nodes of the
    /// objects inserted after the scene's hierarchy was built: Hierarchy::attachObject).
    LeafMesh(const Hierarchy& h, int firstNode);

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

    /// The value at x on `polygon` interpolated from per-vertex `values`.
    Rgb interpolate(const std::vector<Rgb>& values, int polygon, const Vec3& x) const;

    /// Per-vertex values by the Gouraud rule: the area-weighted mean of the leaf values
    /// `leafValue(node)` over the leaves that have the vertex as a corner.
    std::vector<Rgb> averageOfLeaves(const std::function<Rgb(int leaf)>& leafValue) const;

    /// A point at vertex v moved a tiny step (1e-4 of the leaf's radius) towards the centre
    /// of one leaf that owns it: inside the polygon, so that rays and point location from
    /// it never start exactly on a polygon edge.
    Vec3 insidePoint(int v) const;

  private:
    const Hierarchy& h_;
    std::vector<Vertex> vertices_;
    std::vector<std::array<int, 4>> corners_;  // by node id; -1 where not a leaf element
    std::vector<int> ownerLeaf_;               // by vertex: one leaf having it as a corner
};

}  // namespace radiosity
