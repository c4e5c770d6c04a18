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

}  // namespace radiosity
