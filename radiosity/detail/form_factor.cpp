// Form factors by Lambert's contour integral; see form_factor.h for units and conventions.
//
// The point-to-polygon form factor of a planar polygon seen from a differential area dA_x
// with unit normal n is (Lambert 1760; Hanrahan, Salzman & Aupperle 1991, "A rapid
// hierarchical radiosity algorithm"; Cohen & Wallace 1993, Radiosity and Realistic Image
// Synthesis, §4):
//
//     F_{dA_x -> P} = 1/(2 pi) * sum_i  gamma_i * n . (R_{i+1} x R_i) / |R_{i+1} x R_i|
//
// with R_i = P_i - x and gamma_i the angle between R_i and R_{i+1}. Each term is the
// projected solid angle of the "wedge" spanned by one edge and x; the sum is exact for any
// planar polygon that lies entirely in front of the receiver. A polygon partly behind the
// receiver's horizon would make the formula count the hidden part negatively, so the source
// is first clipped to the receiver's half-space (Sutherland-Hodgman against one plane).
#include "radiosity/detail/form_factor.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace radiosity {

namespace {

/// Relative size of the clipping offset: the source is clipped to n.(y - x) > eps with
/// eps = kRelClip * (largest |P_i - x| coordinate). Points in (or within rounding of) the
/// receiver's plane are thus clipped, so no clipped corner can coincide with x and every
/// R_i is non-zero. The discarded sliver is at most eps thick next to the horizon where the
/// receiver's cosine is itself ~eps / distance, so it changes F by O(1e-24): far below the
/// 1e-9 closed-enclosure sum the tests check.
constexpr double kRelClip = 1e-12;

/// Streams the corners of the clipped polygon and sums the contour terms edge by edge, so
/// that clipping needs no vertex buffer at all: pointToPolygon is allocation-free for any
/// corner count (a clip against one plane emits at most count + 1 corners, in order).
class ContourSum {
  public:
    explicit ContourSum(const Vec3& n) : n_(n) {}

    void add(const Vec3& r) {
        if (k_ == 0)
            first_ = r;
        else
            sum_ += edgeTerm(prev_, r);
        prev_ = r;
        ++k_;
    }

    /// Closes the contour; returns the form factor, clamped to [0, 1] against rounding.
    double finish() {
        if (k_ < 3) return 0;  // clipped to nothing (or to a degenerate sliver)
        sum_ += edgeTerm(prev_, first_);
        double f = sum_ / (2 * std::numbers::pi);
        if (!(f > 0)) return 0;  // also catches NaN from non-finite input
        return std::min(f, 1.0);
    }

  private:
    /// Contribution of the edge from corner a to corner b (both relative to x).
    double edgeTerm(const Vec3& a, const Vec3& b) const {
        // b x a (not a x b): for corners counter-clockwise seen from the source's front and x
        // in front, this points into the receiver's hemisphere, making F positive.
        Vec3 c = glm::cross(b, a);
        double cl = glm::length(c);
        // An edge whose line passes through x spans no solid angle: its plane with x is
        // undefined and its angle is 0 (clipping keeps x off the polygon, so never pi).
        if (!(cl > std::numeric_limits<double>::min())) return 0;
        // atan2(|a x b|, a.b) keeps full relative precision for small angles, where
        // acos(a.b / |a||b|) would lose half the digits.
        double gamma = std::atan2(cl, glm::dot(a, b));
        return gamma * glm::dot(n_, c) / cl;
    }

    Vec3 n_;
    Vec3 first_{0, 0, 0};
    Vec3 prev_{0, 0, 0};
    double sum_ = 0;
    int k_ = 0;
};

constexpr int kMaxOrder = 16;

/// Gauss-Legendre nodes and weights on [0, 1] for orders 1..kMaxOrder; weights sum to 1.
struct GaussLegendreTable {
    std::array<std::array<double, kMaxOrder>, kMaxOrder + 1> node{};
    std::array<std::array<double, kMaxOrder>, kMaxOrder + 1> weight{};

    GaussLegendreTable() {
        for (int n = 1; n <= kMaxOrder; ++n) {
            // Newton iteration on the Legendre polynomial P_n from the classical asymptotic
            // guess (Numerical Recipes, gauleg); roots are symmetric, so solve half of them.
            for (int i = 0; i < (n + 1) / 2; ++i) {
                double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
                double dp = 1;
                for (int iter = 0; iter < 100; ++iter) {
                    double p1 = 1, p2 = 0;
                    for (int j = 1; j <= n; ++j) {
                        double p3 = p2;
                        p2 = p1;
                        p1 = ((2 * j - 1) * z * p2 - (j - 1) * p3) / j;
                    }
                    // P_n'(z) = n (z P_n - P_{n-1}) / (z^2 - 1); |z| < 1 strictly here.
                    dp = n * (z * p1 - p2) / (z * z - 1);
                    double dz = p1 / dp;
                    z -= dz;
                    if (std::abs(dz) < 1e-16) break;
                }
                // Weight on [-1, 1] is 2 / ((1 - z^2) P_n'^2); halve it for [0, 1].
                double w = 1 / ((1 - z * z) * dp * dp);
                node[n][i] = 0.5 * (1 - z);
                node[n][n - 1 - i] = 0.5 * (1 + z);
                weight[n][i] = w;
                weight[n][n - 1 - i] = w;
            }
        }
    }
};

const GaussLegendreTable& gaussLegendre() {
    static const GaussLegendreTable table;  // thread-safe one-time initialisation
    return table;
}

}  // namespace

double pointToPolygon(const Vec3& x, const Vec3& n, const Vec3* P, int count, const Vec3& pn) {
    if (P == nullptr || count < 3) return 0;

    // Size of the configuration seen from x, to make the clipping offset scale-free.
    double scale = 0;
    for (int i = 0; i < count; ++i) {
        Vec3 r = glm::abs(P[i] - x);
        scale = std::max({scale, r.x, r.y, r.z});
    }
    if (!(scale > 0) || !std::isfinite(scale)) return 0;
    const double eps = kRelClip * scale;

    // One-sided source: only a point strictly in front of its plane sees it. The same
    // relative tolerance treats a point in the source's plane (e.g. a coplanar neighbour)
    // as not in front, whatever the rounding of its coordinates.
    if (!(glm::dot(pn, x - P[0]) > eps)) return 0;

    // Sutherland-Hodgman against h(y) = n.(y - x) - eps > 0, streamed into the contour sum:
    // for each edge a -> b emit the crossing (if the edge crosses the plane), then b (if in).
    ContourSum contour(n);
    Vec3 a = P[count - 1] - x;
    double ha = glm::dot(n, a) - eps;
    for (int i = 0; i < count; ++i) {
        Vec3 b = P[i] - x;
        double hb = glm::dot(n, b) - eps;
        if ((ha > 0) != (hb > 0)) {
            // ha and hb have opposite signs (one may be 0), so ha - hb != 0.
            double t = ha / (ha - hb);
            contour.add(a + t * (b - a));
        }
        if (hb > 0) contour.add(b);
        a = b;
        ha = hb;
    }
    return contour.finish();
}

QuadratureRule quadrature(const Vec3* P, int count, int order) {
    assert(count == 3 || count == 4);
    assert(order >= 1 && order <= kMaxOrder);
    QuadratureRule rule;
    if (P == nullptr || (count != 3 && count != 4)) return rule;
    order = std::clamp(order, 1, kMaxOrder);
    const auto& gl = gaussLegendre();
    const auto& u = gl.node[order];
    const auto& w = gl.weight[order];

    rule.points.reserve(order * order);
    rule.weights.reserve(order * order);
    double total = 0;
    for (int i = 0; i < order; ++i) {
        for (int j = 0; j < order; ++j) {
            Vec3 p;
            double jac;
            if (count == 3) {
                // Collapsed (Duffy) square: (s, t) -> P0 + s ((1 - t)(P1 - P0) + t (P2 - P0)),
                // Jacobian 2 A s; the edge s = 0 collapses onto corner P0.
                double s = u[i], t = u[j];
                p = P[0] + s * ((1 - t) * (P[1] - P[0]) + t * (P[2] - P[0]));
                jac = s;  // the constant 2A cancels in the normalisation
            } else {
                // Bilinear map of the quad; its Jacobian is exact for planar convex quads.
                double s = u[i], t = u[j];
                p = (1 - s) * (1 - t) * P[0] + s * (1 - t) * P[1] + s * t * P[2] +
                    (1 - s) * t * P[3];
                Vec3 ds = (1 - t) * (P[1] - P[0]) + t * (P[2] - P[3]);
                Vec3 dt = (1 - s) * (P[3] - P[0]) + s * (P[2] - P[1]);
                jac = glm::length(glm::cross(ds, dt));
            }
            double wt = w[i] * w[j] * jac;
            rule.points.push_back(p);
            rule.weights.push_back(wt);
            total += wt;
        }
    }
    // Normalise to sum 1. A degenerate (zero-area) polygon has all Jacobians 0: fall back to
    // the plain tensor weights so the rule stays a valid average.
    if (total > 0) {
        for (double& wt : rule.weights) wt /= total;
    } else {
        for (int i = 0; i < order; ++i)
            for (int j = 0; j < order; ++j) rule.weights[i * order + j] = w[i] * w[j];
    }
    return rule;
}

double polygonToPolygon(const Vec3* R, int rc, const Vec3& rn, const Vec3* S, int sc,
                        const Vec3& sn, int order) {
    QuadratureRule rule = quadrature(R, rc, order);
    double f = 0;
    for (std::size_t k = 0; k < rule.points.size(); ++k)
        f += rule.weights[k] * pointToPolygon(rule.points[k], rn, S, sc, sn);
    return std::clamp(f, 0.0, 1.0);
}

double discFormFactor(double cosR, double cosS, double d2, double areaS) {
    // The source is replaced by a disc of area A_s facing the receiver, whose exact
    // on-axis form factor is A_s / (pi d^2 + A_s); the cosines tilt it. The A_s in the
    // denominator keeps the estimate <= 1 and finite as d -> 0, unlike A_s cos cos/(pi d^2).
    cosR = std::clamp(cosR, 0.0, 1.0);
    cosS = std::clamp(cosS, 0.0, 1.0);
    areaS = std::max(areaS, 0.0);
    double denom = std::numbers::pi * std::max(d2, 0.0) + areaS;
    if (!(denom > 0)) return 0;  // zero area at zero distance (or NaN input)
    double f = cosR * cosS * areaS / denom;
    return f > 0 ? std::min(f, 1.0) : 0.0;
}

}  // namespace radiosity
