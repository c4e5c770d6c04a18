// Cosine-distributed directions over a hemisphere, stratified: Malley's method (points
// uniform on the unit disc, lifted to the hemisphere, are cosine-distributed) with strata
// of a k x k grid on the square mapped to the disc by the concentric map (Shirley & Chiu
// 1997). The energy bound's measure of what a leaf sees (energy_bound.cpp) and the reach
// of a light (light_reach.cpp) cast their rays with it.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radiosity/detail/rng.h"
#include "radiosity/vec.h"

namespace radiosity {

/// An orthonormal frame about a unit normal n: tangents t and b with t x b = n.
struct HemisphereFrame {
    Vec3 t, b, n;
    explicit HemisphereFrame(const Vec3& normal)
        : t(glm::normalize(std::abs(normal.x) < 0.9 ? glm::cross(normal, Vec3{1, 0, 0})
                                                    : glm::cross(normal, Vec3{0, 1, 0}))),
          b(glm::cross(normal, t)),
          n(normal) {}
};

/// A cosine-distributed direction in stratum `cell` of a k x k grid (0 <= cell < k*k),
/// jittered within the stratum by two draws of `rng`.
inline Vec3 cosineDirection(const HemisphereFrame& f, int cell, int k, Rng& rng) {
    const double a = 2 * ((cell % k) + rng.uniform()) / k - 1;
    const double c = 2 * ((cell / k) + rng.uniform()) / k - 1;
    // Concentric square-to-disc map.
    double r = 0, phi = 0;
    if (std::abs(a) > std::abs(c)) {
        r = a;
        phi = (std::numbers::pi / 4) * (c / a);
    } else if (c != 0) {
        r = c;
        phi = std::numbers::pi / 2 - (std::numbers::pi / 4) * (a / c);
    }
    const double x = r * std::cos(phi), y = r * std::sin(phi);
    const double z = std::sqrt(std::max(0.0, 1 - x * x - y * y));
    return x * f.t + y * f.b + z * f.n;
}

/// Where in the square of cosineDirection's strata ([-1, 1]^2, cell = i + k j covering
/// a in [2i/k - 1, 2(i+1)/k - 1], c likewise with j) the directions toward a ball (a face's
/// bounding sphere) may lie, so that a gather can skip testing that face on the other rays.
/// A direction within angle beta of the ball's axis w projects onto the tangent plane within
/// the chord 2 sin(beta / 2) of w's projection (projection does not stretch distances), and
/// the inverse concentric map stretches distances on the disc by at most ~1.9 (the Frobenius
/// norm of its Jacobian: sqrt(2 + (4/pi)^2) on each of its four pieces, continuous across
/// them): within 2.5 chords of w's point in the square (a margin for the bound).
struct StrataWindow {
    double a = 0, c = 0, radius = -1;  ///< radius < 0: the whole square
    bool everywhere() const { return radius < 0; }

    static StrataWindow toward(const HemisphereFrame& f, const Vec3& origin, const Vec3& centre,
                               double ballRadius) {
        StrataWindow w;
        const Vec3 to = centre - origin;
        const double dist = glm::length(to);
        if (!(dist > ballRadius * (1 + 1e-9)) || !(dist > 0)) return w;  // inside: anywhere
        const double beta = std::asin(std::min(1.0, ballRadius / dist));
        const Vec3 axis = to / dist;
        const double x = glm::dot(axis, f.t), y = glm::dot(axis, f.b);
        const double rho = std::min(1.0, std::hypot(x, y));
        const double pi = std::numbers::pi;
        // The inverse of the concentric map (cosineDirection): (x, y) on the disc -> (a, c).
        double theta = rho > 0 ? std::atan2(y, x) : 0.0;
        if (theta < -pi / 4) theta += 2 * pi;  // in [-pi/4, 7pi/4)
        if (theta < pi / 4) {
            w.a = rho;
            w.c = rho * theta * 4 / pi;
        } else if (theta < 3 * pi / 4) {
            w.c = rho;
            w.a = rho * (pi / 2 - theta) * 4 / pi;
        } else if (theta < 5 * pi / 4) {
            w.a = -rho;
            w.c = -rho * (theta - pi) * 4 / pi;
        } else {
            w.c = -rho;
            w.a = -rho * (pi / 2 - (theta - pi)) * 4 / pi;
        }
        w.radius = 2.5 * 2 * std::sin(beta / 2) + 1e-9;
        return w;
    }

    /// False when no direction of stratum `cell` of a k x k grid can meet the ball.
    bool mayHold(int cell, int k) const {
        if (everywhere()) return true;
        const double i = cell % k, j = cell / k;
        const double a0 = 2 * i / k - 1, a1 = 2 * (i + 1) / k - 1;
        const double c0 = 2 * j / k - 1, c1 = 2 * (j + 1) / k - 1;
        const double da = a < a0 ? a0 - a : (a > a1 ? a - a1 : 0.0);
        const double dc = c < c0 ? c0 - c : (c > c1 ? c - c1 : 0.0);
        return da * da + dc * dc <= radius * radius;
    }
};

}  // namespace radiosity
