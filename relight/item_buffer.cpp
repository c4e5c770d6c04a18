#include "relight/item_buffer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

namespace relight {

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
    tbb::parallel_for(tbb::blocked_range<int>(0, items.height),
                      [&](const tbb::blocked_range<int>& rows) {
                          for (int y = rows.begin(); y != rows.end(); ++y) {
                              for (int x = 0; x < items.width; ++x) {
                                  for (int s = 0; s < items.spp; ++s) {
                                      const double u = x - 0.5 + ((s % k) + 0.5) / k;
                                      const double v = y - 0.5 + ((s / k) + 0.5) / k;
                                      const radiosity::Vec3 dir = camera.rayDirection(u, v);
                                      const auto hit = vis.intersect(eye, dir);
                                      const int idx = items.sampleIndex(x, y, s);
                                      if (hit.polygon < 0) continue;
                                      // One-sided surfaces: the back of a polygon shows nothing.
                                      if (glm::dot(scene.polygons[hit.polygon].normal, dir) >= 0)
                                          continue;
                                      items.polygon[idx] = hit.polygon;
                                      items.point[idx] = eye + hit.t * dir;
                                  }
                              }
                          }
                      });
    return items;
}

}  // namespace relight
