// Sky transfer: how much of an order-2 sky (radiosity/sh9.h) reaches a point, with the
// scene's geometry in the way (Sloan, Kautz & Snyder 2002, shadowed diffuse transfer).
//
// The transfer vector of a point p with normal n is
//     T_k = integral over the sphere of V(p, w) Y_k(w) max(0, n.w) dw,
// V(p, w) = 1 where the ray from p along w escapes the scene. The irradiance the sky
// L(w) = sum_k L_k Y_k(w) gives p is then the 9-term dot product E(p) = sum_k T_k L_k
// (sh9Dot), whatever the sky and however it turns. Where nothing occludes, T_k is
// A_l Y_k(n) (sh9CosineTransfer) and E(p) the irradiance of R&H 2001, Eq. 7.
//
// Estimated from rays: N directions w_i drawn with density max(0, n.w) / pi, stratified on
// a k x k grid (radiosity/detail/hemisphere.h), give T_k ~ (pi / N) sum_i V(p, w_i) Y_k(w_i).
// T_0 of an unoccluded point is then exact (Y_0 is constant); the other terms carry the
// stratified estimate's error, which falls faster than 1 / sqrt(N) (sky_transfer_test.cpp
// measures it).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "radiosity/sh9.h"
#include "radiosity/vec.h"
#include "radiosity/visibility.h"

namespace radiosity {

/// A point that receives sky light.
struct SkyPoint {
    Vec3 position;     ///< metres
    Vec3 normal;       ///< the front of the surface there; any finite, non-zero length
    int polygon = -1;  ///< Scene::polygons index p lies on (never its own blocker), or -1
};

struct SkyTransferOptions {
    /// Rays per point, rounded up to a square k x k of strata.
    int rays = 256;
    /// Seeds every point's directions, with the point's index: the same transfer on every
    /// run and with any thread count.
    uint64_t seed = 0x5c7e11ull;
};

/// The transfer vector of `point` (see above), its rays cast against `vis` as segments from
/// the point to beyond `sceneBounds` (the bounds of the scene `vis` holds; empty when the
/// scene is). `index` seeds its directions. Throws std::invalid_argument for a normal that
/// is zero (shorter than 1e-12) or not finite, or fewer than 1 ray.
Sh9 skyTransfer(const Visibility& vis, const Bounds3& sceneBounds, const SkyPoint& point,
                size_t index, const SkyTransferOptions& options = {});

/// skyTransfer() of every point (point i seeded with index i), in parallel. Checks every
/// point before casting a ray: throws std::invalid_argument naming the first bad one.
std::vector<Sh9> skyTransfers(const Visibility& vis, const Bounds3& sceneBounds,
                              std::span<const SkyPoint> points,
                              const SkyTransferOptions& options = {});

}  // namespace radiosity
