#include "radiosity/light_reach.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "radiosity/detail/rng.h"
#include "radiosity/hierarchy.h"

namespace radiosity {

LightReach lightReach(const Scene& scene, const Visibility& vis, int light, int rays) {
    if (light < 0 || light >= static_cast<int>(scene.lights.size()))
        throw std::out_of_range("lightReach: no light " + std::to_string(light));
    const Light& L = scene.lights[static_cast<size_t>(light)];
    const double diag = glm::length(scene.bounds().diagonal());
    const double tMin = 1e-6 * diag;  // above Embree's float rounding (visibility.h)
    const int faces = static_cast<int>(L.polygons.size());
    const int k = strataSide(std::max(16, rays / std::max(faces, 1)));
    Rng rng(0x11647ull ^ (static_cast<uint64_t>(light) * 0x9E3779B97F4A7C15ull));
    LightReach reach;
    double area = 0, reached = 0;
    for (const int f : L.polygons) {
        const Polygon& face = scene.polygons[static_cast<size_t>(f)];
        // Cosine-distributed directions as the solver's measureSeen casts them: strata of a
        // k x k grid mapped to the disc (concentric map) and lifted to the hemisphere.
        const Vec3 n = face.normal;
        const Vec3 t = glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, Vec3{1, 0, 0})
                                                          : glm::cross(n, Vec3{0, 1, 0}));
        const Vec3 b = glm::cross(n, t);
        int hits = 0;
        for (int cell = 0; cell < k * k; ++cell) {
            const double a = 2 * ((cell % k) + rng.uniform()) / k - 1;
            const double c = 2 * ((cell / k) + rng.uniform()) / k - 1;
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
            const Vec3 dir = x * t + y * b + z * n;
            const Vec3 org = pointOnPolygon(face, rng.uniform(), rng.uniform());
            const Visibility::Hit hit = vis.intersect(org, dir, tMin);
            if (hit.polygon < 0 || hit.polygon == f) continue;
            const Polygon& p = scene.polygons[static_cast<size_t>(hit.polygon)];
            if (p.light < 0 && glm::dot(p.normal, dir) < 0) ++hits;
        }
        reach.rays += k * k;
        reach.hits += hits;
        area += face.area;
        reached += face.area * hits / (k * k);
    }
    reach.fraction = area > 0 ? reached / area : 0;
    return reach;
}

}  // namespace radiosity
