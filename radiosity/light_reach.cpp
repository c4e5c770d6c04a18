#include "radiosity/light_reach.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "radiosity/detail/hemisphere.h"
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
        // Cosine-distributed directions, as the energy bound casts them (detail/hemisphere.h).
        const HemisphereFrame frame(face.normal);
        int hits = 0;
        for (int cell = 0; cell < k * k; ++cell) {
            const Vec3 dir = cosineDirection(frame, cell, k, rng);
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
