// Shaft culling, Haines & Wallace 1991, "Shaft culling for efficient ray-traced radiosity",
// Sec. 3 (box-to-box shafts) and Sec. 4 (testing objects against the shaft).
//
// Construction (H&W Sec. 3): the shaft is the union box of the two boxes A and B, cut by a
// plane at each "silhouette" edge pair. Take two axes i < j and one side (min or max) on
// each. If A reaches farther than B on that side of axis i but less far on that side of
// axis j (or the other way round), the two boxes' edges parallel to the third axis at that
// corner form a silhouette of the pair: the plane through both edges bounds the convex hull
// of A and B, and the union box alone would leave a wedge of empty space at that corner.
// With 3 axis pairs x 4 corners and at most 8 that qualify, the shaft has at most 8 planes.
// Each plane's normal lies in the (i, j) plane and points away from both boxes, and each
// box's most extreme point along it is exactly its silhouette edge, so both boxes -- hence
// their convex hull -- lie inside.
//
// Test (H&W Sec. 4): a box is culled when it misses the union box, or when even its corner
// farthest inside a plane (the "p-vertex", chosen per axis by the sign of the normal) is
// outside that plane. This is conservative: a box straddling two planes outside their
// intersection is kept.
//
// Differs from H&W: every plane and the union box are loosened by a small tolerance
// (tolerance_, 1e-9 of the scene scale) so that points computed on the hull's boundary in
// floating point, e.g. the end points of a segment between two boxes, are never culled.
#include "radiosity/detail/shaft.h"

#include <algorithm>
#include <cmath>

namespace radiosity {

namespace {

// Coordinate of box b's side s (0: min, 1: max) on axis.
double side(const Bounds3& b, int axis, int s) {
    return s ? b.hi[axis] : b.lo[axis];
}

}  // namespace

Shaft::Shaft(const Bounds3& a, const Bounds3& b) {
    box_ = a;
    box_.extend(b);
    if (box_.empty()) {
        looseBox_ = box_;
        return;
    }
    // Tolerance: 1e-9 of the boxes' size and distance from the origin (10 nm in a 10 m
    // room), far above double rounding (~1e-16 relative) and far below any geometry.
    const Vec3 reach = glm::max(glm::abs(box_.lo), glm::abs(box_.hi));
    tolerance_ =
        1e-9 * (std::max(reach.x, std::max(reach.y, reach.z)) + glm::length(box_.diagonal()));
    looseBox_.lo = box_.lo - Vec3(tolerance_);
    looseBox_.hi = box_.hi + Vec3(tolerance_);
    // With an empty box there is nothing to join: the shaft is the other box.
    if (a.empty() || b.empty()) return;

    for (int i = 0; i < 3; ++i) {
        for (int j = i + 1; j < 3; ++j) {
            for (int si = 0; si < 2; ++si) {
                for (int sj = 0; sj < 2; ++sj) {
                    // Outward direction of this corner of the union box in the (i, j) plane.
                    const double ui = si ? 1.0 : -1.0;
                    const double uj = sj ? 1.0 : -1.0;
                    // Which box reaches farther out on each axis: +1 A, -1 B, 0 tie.
                    auto farther = [&](int axis, int s, double u) {
                        const double da = u * side(a, axis, s);
                        const double db = u * side(b, axis, s);
                        return da > db ? 1 : (da < db ? -1 : 0);
                    };
                    // Silhouette only when a different box is the outer one on each axis
                    // (H&W Sec. 3); on a tie the union box's face already is tight.
                    if (farther(i, si, ui) * farther(j, sj, uj) >= 0) continue;
                    // The edges of A and B at this corner, projected on (i, j).
                    const double ai = side(a, i, si), aj = side(a, j, sj);
                    const double bi = side(b, i, si), bj = side(b, j, sj);
                    // Normal of the line through the two projected edges, pointing out of
                    // the corner; it is nonzero since the edges differ on both axes.
                    double ni = bj - aj, nj = -(bi - ai);
                    if (ni * ui + nj * uj < 0) {
                        ni = -ni;
                        nj = -nj;
                    }
                    const double length = std::hypot(ni, nj);
                    Plane plane;
                    plane.n[i] = ni / length;
                    plane.n[j] = nj / length;
                    plane.d = plane.n[i] * ai + plane.n[j] * aj + tolerance_;
                    planes_[planeCount_++] = plane;
                }
            }
        }
    }
}

bool Shaft::contains(const Vec3& p) const {
    if (p.x < looseBox_.lo.x || p.x > looseBox_.hi.x || p.y < looseBox_.lo.y ||
        p.y > looseBox_.hi.y || p.z < looseBox_.lo.z || p.z > looseBox_.hi.z)
        return false;
    for (int k = 0; k < planeCount_; ++k)
        if (glm::dot(planes_[k].n, p) > planes_[k].d) return false;
    return true;
}

bool Shaft::mayIntersect(const Bounds3& box) const {
    if (box.empty() || box_.empty() || !looseBox_.overlaps(box)) return false;
    for (int k = 0; k < planeCount_; ++k) {
        const Plane& plane = planes_[k];
        // p-vertex: the corner of `box` farthest to the inside of the plane (H&W Sec. 4).
        const Vec3 inner{plane.n.x >= 0 ? box.lo.x : box.hi.x, plane.n.y >= 0 ? box.lo.y : box.hi.y,
                         plane.n.z >= 0 ? box.lo.z : box.hi.z};
        if (glm::dot(plane.n, inner) > plane.d) return false;
    }
    return true;
}

}  // namespace radiosity
