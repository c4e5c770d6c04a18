#include "radiosity/sky_transfer.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/rng.h"
#include "radiosity/parallel.h"

namespace radiosity {

namespace {

// The unit normal of a point, or an exception naming it.
Vec3 unitNormal(const SkyPoint& p, size_t index) {
    const double len = glm::length(p.normal);
    if (!std::isfinite(len) || len < 1e-12)
        throw std::invalid_argument("sky transfer: point " + std::to_string(index) +
                                    " has a zero or non-finite normal");
    return p.normal / len;
}

void checkOptions(const SkyTransferOptions& options) {
    if (options.rays < 1) throw std::invalid_argument("sky transfer: rays must be at least 1");
}

// Length of the segments: from p to beyond every polygon of the scene. A point of the
// bounds lies within |p - c| + |diagonal| / 2 of p; the margin of 1 m keeps the far end
// off the bounds' faces (and serves an empty scene, where nothing occludes).
double reach(const Bounds3& bounds, const Vec3& p) {
    if (bounds.empty()) return 1.0;
    return glm::length(p - bounds.centre()) + glm::length(bounds.diagonal()) + 1.0;
}

}  // namespace

Sh9 skyTransfer(const Visibility& vis, const Bounds3& sceneBounds, const SkyPoint& point,
                size_t index, const SkyTransferOptions& options) {
    checkOptions(options);
    const Vec3 n = unitNormal(point, index);
    const HemisphereFrame frame(n);
    const int k = strataSide(options.rays), rays = k * k;
    Rng rng(options.seed ^ (static_cast<uint64_t>(index) * 0x9E3779B97F4A7C15ull));
    const double length = reach(sceneBounds, point.position);

    std::vector<Vec3> dirs(static_cast<size_t>(rays)), from(dirs.size(), point.position),
        to(dirs.size());
    for (int cell = 0; cell < rays; ++cell) {
        const size_t i = static_cast<size_t>(cell);
        dirs[i] = cosineDirection(frame, cell, k, rng);
        to[i] = point.position + length * dirs[i];
    }
    // visibleBatch writes bools; std::vector<bool> has no contiguous storage.
    const std::unique_ptr<bool[]> out = std::make_unique<bool[]>(dirs.size());
    vis.visibleBatch(from.data(), to.data(), rays, out.get(), point.polygon);

    // The estimator of sky_transfer.h: with density cos / pi, each ray weighs pi / N.
    Sh9 T{};
    for (size_t i = 0; i < dirs.size(); ++i) {
        if (!out[i]) continue;
        const Sh9 y = sh9Basis(dirs[i]);
        for (int c = 0; c < kSh9Count; ++c) T[c] += y[c];
    }
    const double weight = std::numbers::pi / rays;
    for (double& t : T) t *= weight;
    return T;
}

std::vector<Sh9> skyTransfers(const Visibility& vis, const Bounds3& sceneBounds,
                              std::span<const SkyPoint> points, const SkyTransferOptions& options) {
    checkOptions(options);
    for (size_t i = 0; i < points.size(); ++i) unitNormal(points[i], i);
    std::vector<Sh9> T(points.size());
    parallelFor(points.size(), 4,
                [&](size_t i) { T[i] = skyTransfer(vis, sceneBounds, points[i], i, options); });
    return T;
}

}  // namespace radiosity
