#include "relight/pipeline/item_buffer.h"

#include <algorithm>
#include <cmath>

#include "radiosity/parallel.h"

namespace relight {

SamplingPlan planSampling(int width, int height, int spp, int64_t budget) {
    SamplingPlan plan;
    int k = std::max(1, static_cast<int>(std::floor(std::sqrt(std::max(1, spp)))));
    const int64_t pixels = static_cast<int64_t>(width) * height;
    if (budget > 0)
        while (k > 1 && int64_t{k} * k * pixels > budget) --k;
    plan.spp = k * k;
    if (budget > 0) {
        auto samples = [&](int s) {
            return int64_t{(width + s - 1) / s} * ((height + s - 1) / s) * plan.spp;
        };
        while (samples(plan.stride) > budget) ++plan.stride;
    }
    return plan;
}

ItemBuffer castItemBuffer(const Camera& camera, const radiosity::Scene& scene,
                          const radiosity::Visibility& vis, int spp) {
    ItemBuffer items;
    items.width = camera.width;
    items.height = camera.height;
    const int k = std::max(1, static_cast<int>(std::floor(std::sqrt(std::max(1, spp)))));
    items.spp = k * k;
    const size_t n = static_cast<size_t>(items.width) * items.height * items.spp;
    items.polygon.assign(n, -1);
    items.point.assign(n, radiosity::Vec3{0, 0, 0});
    const radiosity::Vec3 eye = camera.position();
    radiosity::parallelForChunks(
        static_cast<size_t>(items.height), 1, [&](size_t first, size_t last) {
            for (int y = static_cast<int>(first); y != static_cast<int>(last); ++y) {
                for (int x = 0; x < items.width; ++x) {
                    for (int s = 0; s < items.spp; ++s) {
                        const double u = x - 0.5 + ((s % k) + 0.5) / k;
                        const double v = y - 0.5 + ((s / k) + 0.5) / k;
                        const radiosity::Vec3 dir = camera.rayDirection(u, v);
                        // One-sided surfaces: the back of a polygon shows nothing, but a thin
                        // part's other face, back to back with it, does (a frame, a banister
                        // modelled as a sheet showed as a hole in the photo's model).
                        const auto found = radiosity::intersectFront(vis, scene, eye, dir);
                        const auto& hit = found.hit;
                        const int idx = items.sampleIndex(x, y, s);
                        if (!found.front) continue;
                        items.polygon[idx] = hit.polygon;
                        items.point[idx] = eye + hit.t * dir;
                    }
                }
            }
        });
    return items;
}

std::vector<double> seenPolygons(const ItemBuffer& items, const radiosity::Scene& scene) {
    std::vector<double> seen(scene.polygons.size(), 0.0);
    for (const int p : items.polygon)
        if (p >= 0 && static_cast<size_t>(p) < seen.size()) seen[static_cast<size_t>(p)] = 1.0;
    return seen;
}

}  // namespace relight
