// Form factors: the geometric coupling between a receiver and a source polygon, unoccluded.
//
// Units and conventions shared by every function below:
//   - Points (x, polygon corners P, R, S) are in world space, metres.
//   - Normals (n, pn, rn, sn) are unit vectors (dimensionless); a surface receives and emits
//     on the side its normal points to only (one-sided, as in scene.h).
//   - Polygon corners run counter-clockwise seen from the front (the side the normal points
//     to); `count`, `rc`, `sc` are corner counts. Polygons are planar and convex.
//   - Areas are in m^2, squared distances in m^2, cosines are dimensionless.
//   - Every form factor returned is dimensionless, in [0, 1]: the fraction of the power
//     leaving a Lambertian receiver element that arrives at the source (equivalently, by
//     reciprocity, the weight with which the source's radiosity reaches the receiver).
//
// Parameters:
//   pointToPolygon(x, n, P, count, pn)
//     x      receiver point (m)
//     n      receiver unit normal; only the half-space {y : n.(y - x) > 0} is seen
//     P      source corners (m), counter-clockwise seen from the source's front
//     count  number of corners, >= 3 (any count; no heap allocation for any count)
//     pn     source unit front normal
//   quadrature(P, count, order)
//     P      corners (m) of a triangle (count 3) or planar convex quad (count 4)
//     order  Gauss-Legendre points per direction, 1..16 (order^2 points in all)
//   polygonToPolygon(R, rc, rn, S, sc, sn, order)
//     R, rc, rn  receiver corners (m), corner count (3 or 4), unit front normal
//     S, sc, sn  source corners (m), corner count (>= 3), unit front normal
//     order      quadrature order on the receiver, as for quadrature()
//   discFormFactor(cosR, cosS, d2, areaS)
//     cosR   cosine between the receiver normal and the direction to the source (clamped >= 0)
//     cosS   cosine between the source normal and the direction to the receiver (clamped >= 0)
//     d2     squared distance between the two sample points (m^2)
//     areaS  source area (m^2)
#pragma once

#include <vector>

#include "radiosity/vec.h"

namespace radiosity {

/// Point-to-polygon form factor F_{dA_x -> P} by Lambert's contour integral (exact for a
/// planar convex polygon): receiver point x with unit normal n (receives on its front only);
/// source polygon P given by `count` corners counter-clockwise seen from its front, with
/// unit normal `pn`; P is one-sided: returns 0 when x is not strictly in front of P's plane.
/// P is first clipped to the receiver's half-space {y : n.(y - x) > 0} so a source partly
/// behind the receiver's horizon is handled exactly. Result in [0, 1].
double pointToPolygon(const Vec3& x, const Vec3& n, const Vec3* P, int count, const Vec3& pn);

/// Quadrature rule over a triangle (count 3) or planar convex quad (count 4): `order`
/// Gauss-Legendre points per direction (order in 1..16), on the bilinear map of the quad,
/// or on the collapsed (Duffy) square for a triangle; weights sum to 1 (area-normalised).
/// Points are strictly inside the polygon.
struct QuadratureRule {
    std::vector<Vec3> points;
    std::vector<double> weights;
};
QuadratureRule quadrature(const Vec3* P, int count, int order);

/// Area-to-area form factor F_{R -> S} = (1/A_R) Int_R F_{dA -> S} dA: pointToPolygon averaged
/// with quadrature(R, rc, order). Unoccluded.
double polygonToPolygon(const Vec3* R, int rc, const Vec3& rn, const Vec3* S, int sc,
                        const Vec3& sn, int order);

/// Unoccluded point-to-point form-factor estimate used by refinement oracles: the "disc"
/// approximation F ~ A_s cos_r cos_s / (pi d^2 + A_s), bounded by 1 and finite for d -> 0.
/// cosR, cosS clamped at 0.
double discFormFactor(double cosR, double cosS, double d2, double areaS);

}  // namespace radiosity
