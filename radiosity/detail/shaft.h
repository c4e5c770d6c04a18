// Shaft between two axis-aligned boxes, for culling: which objects may block the light
// exchanged between a source and a receiver (Haines & Wallace 1991, "Shaft culling for
// efficient ray-traced radiosity").
//
// API
//   Shaft shaft(sourceBounds, receiverBounds);   // metres, world space
//   shaft.mayIntersect(box)  // false only when box lies entirely outside the shaft
//   shaft.contains(p)        // point inside the shaft (tests, debugging)
//
// The shaft is the union box of the two boxes cut by up to 8 planes, each through an edge
// of one box and the parallel edge of the other; it contains the convex hull of the two
// boxes (so every segment from a point of one box to a point of the other) and is convex.
// It may be larger than the hull: culling is conservative, never wrong.
#pragma once

#include <array>

#include "radiosity/vec.h"

namespace radiosity {

class Shaft {
  public:
    /// Builds the shaft of boxes a and b (metres). Flat boxes (zero extent on an axis, as
    /// the bounds of an axis-aligned polygon) and overlapping or identical boxes are fine.
    Shaft(const Bounds3& a, const Bounds3& b);

    /// Conservative test: false only if `box` lies entirely outside the shaft (outside the
    /// union box, or wholly on the outer side of one plane). May say true for a box that
    /// misses the shaft near its edges, as H&W's test does.
    bool mayIntersect(const Bounds3& box) const;

    /// True when p is inside the shaft, up to the tolerance of the constructor (points on
    /// the boundary are inside).
    bool contains(const Vec3& p) const;

    /// The union box of the two boxes (without tolerance).
    const Bounds3& bounds() const { return box_; }
    /// Number of planes, 0 to 8 (0 when one box contains the other or they are aligned).
    int planeCount() const { return planeCount_; }

  private:
    /// Half-space n . x <= d (n unit, x and d in metres): the inside of the shaft.
    struct Plane {
        Vec3 n{0, 0, 0};
        double d = 0;
    };

    Bounds3 box_;                  ///< union box of the two boxes, metres
    Bounds3 looseBox_;             ///< box_ grown by tolerance_ on every side, for the tests
    std::array<Plane, 8> planes_;  ///< first planeCount_ used; d already includes tolerance_
    int planeCount_ = 0;
    double tolerance_ = 0;  ///< metres; absorbs rounding of points computed on the boundary
};

}  // namespace radiosity
