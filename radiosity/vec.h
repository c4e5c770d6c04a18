// Geometry types of the radiosity layer: points and vectors in world space, metres.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace radiosity {

/// A point or direction in world space (metres); double precision so that form factors
/// of adjacent, nearly coplanar elements keep their digits.
using Vec3 = glm::dvec3;

/// Axis-aligned bounding box (metres). Empty when lo > hi.
struct Bounds3 {
    Vec3 lo{1e300, 1e300, 1e300};
    Vec3 hi{-1e300, -1e300, -1e300};

    void extend(const Vec3& p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void extend(const Bounds3& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    bool empty() const { return lo.x > hi.x; }
    Vec3 centre() const { return 0.5 * (lo + hi); }
    Vec3 diagonal() const { return hi - lo; }
    bool overlaps(const Bounds3& b) const {
        return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
               lo.z <= b.hi.z && b.lo.z <= hi.z;
    }
    int longestAxis() const {
        Vec3 d = diagonal();
        return d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);
    }
};

}  // namespace radiosity
