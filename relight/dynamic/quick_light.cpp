#include "relight/dynamic/quick_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "radiosity/defaults.h"
#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/rng.h"
#include "radiosity/hierarchy.h"
#include "radiosity/parallel.h"

namespace relight {

namespace {
// The stream of a pixel's quick ray: apart from the exact light's (seeded by the sample).
constexpr uint64_t kQuickSeed = 0x9b1c4a11ull << 20;

/// The item-buffer sample of pixel (x, y) that the quick light measures: the middle one
/// (nearest the pixel's centre of its strata), else the first that sees a reflecting
/// surface, as the exact mean counts them; -1 when none does.
int quickSample(const ItemBuffer& items, const radiosity::Scene& scene, int x, int y) {
    const int spp = items.spp;
    for (int k = 0; k <= spp; ++k) {
        const int s = k == 0 ? spp / 2 : k - 1;
        if (k > 0 && s == spp / 2) continue;
        const int i = items.sampleIndex(x, y, s);
        const int p = items.polygon[static_cast<size_t>(i)];
        if (p >= 0 && scene.polygons[static_cast<size_t>(p)].light < 0) return i;
    }
    return -1;
}

/// Whether a segment from x to a point of polygon q can meet the sphere: the segments lie
/// in the cone from x around q's bounding sphere (apex x, half-angle asin(r_q / |c_q - x|));
/// the sphere meets that cone's neighbourhood of radius `near.radius`. Conservative.
bool mayBlock(const radiosity::Vec3& x, const BoundingSphere& face, const BoundingSphere& near) {
    const radiosity::Vec3& c = face.centre;
    const double rq = face.radius;
    const radiosity::Vec3 axis = c - x, v = near.centre - x;
    const double len = glm::length(axis);
    if (!(len > rq) || glm::length(v) <= near.radius) return true;  // x inside either sphere
    const radiosity::Vec3 a = axis / len;
    const double along = glm::dot(v, a);
    if (along < -near.radius || along > len + rq + near.radius) return false;  // behind, beyond
    const double across = glm::length(v - along * a);
    const double sinT = rq / len, cosT = std::sqrt(std::max(0.0, 1 - sinT * sinT));
    // Distance from the sphere's centre to the cone's surface (negative inside it).
    return across * cosT - along * sinT <= near.radius;
}
}  // namespace

std::vector<float> quickPixelLight(const ItemBuffer& items, const radiosity::Scene& scene,
                                   const radiosity::Visibility& vis,
                                   const radiosity::Emitter& light) {
    const size_t n = static_cast<size_t>(light.components());
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(pixels * n, 0.0f);
    radiosity::parallelForChunks(pixels, 256, [&](size_t first, size_t last) {
        double unit[radiosity::kMaxEmitterComponents] = {};
        for (size_t px = first; px != last; ++px) {
            const int x = static_cast<int>(px % static_cast<size_t>(items.width));
            const int y = static_cast<int>(px / static_cast<size_t>(items.width));
            const int idx = quickSample(items, scene, x, y);
            if (idx < 0) continue;
            const int p = items.polygon[static_cast<size_t>(idx)];
            const radiosity::ReceiverPoint at{items.point[static_cast<size_t>(idx)],
                                              scene.polygons[static_cast<size_t>(p)].normal, p};
            radiosity::Rng rng(kQuickSeed ^ static_cast<uint64_t>(idx));
            light.unitIrradiance(vis, at, 1, rng, unit);
            for (size_t c = 0; c < n; ++c) out[px * n + c] = static_cast<float>(unit[c]);
        }
    });
    return out;
}

std::vector<float> quickReceivers(const ItemBuffer& items, const radiosity::Scene& scene) {
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(6 * pixels, 0.0f);
    radiosity::parallelFor(pixels, 256, [&](size_t px) {
        const int x = static_cast<int>(px % static_cast<size_t>(items.width));
        const int y = static_cast<int>(px / static_cast<size_t>(items.width));
        const int idx = quickSample(items, scene, x, y);
        if (idx < 0) return;
        const radiosity::Vec3& at = items.point[static_cast<size_t>(idx)];
        const radiosity::Vec3& n =
            scene.polygons[static_cast<size_t>(items.polygon[static_cast<size_t>(idx)])].normal;
        for (int c = 0; c < 3; ++c) {
            out[6 * px + static_cast<size_t>(c)] = static_cast<float>(at[c]);
            out[6 * px + 3 + static_cast<size_t>(c)] = static_cast<float>(n[c]);
        }
    });
    return out;
}

double rayFace(const radiosity::Vec3& o, const radiosity::Vec3& d,
               std::span<const radiosity::Vec3> corners, bool* front) {
    constexpr double kNever = std::numeric_limits<double>::infinity();
    if (corners.size() < 3) return kNever;
    const radiosity::Vec3 n = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
    const double dn = glm::dot(n, d);
    if (!(std::abs(dn) > 1e-300)) return kNever;  // guard: a ray along the face's plane
    const double t = glm::dot(n, corners[0] - o) / dn;
    if (!(t > 0)) return kNever;
    const radiosity::Vec3 x = o + t * d;
    for (size_t i = 0; i < corners.size(); ++i) {
        const radiosity::Vec3& a = corners[i];
        const radiosity::Vec3& b = corners[(i + 1) % corners.size()];
        if (glm::dot(glm::cross(b - a, x - a), n) < 0) return kNever;
    }
    if (front) *front = dn < 0;
    return t;
}

FaceCover faceCoverage(const Camera& camera, int k, int x, int y, double shows,
                       std::span<const radiosity::Vec3> corners) {
    FaceCover c;
    const radiosity::Vec3 eye = camera.position();
    const double n = static_cast<double>(k) * k;
    for (int s = 0; s < k * k; ++s) {
        const double u = x - 0.5 + ((s % k) + 0.5) / k, v = y - 0.5 + ((s / k) + 0.5) / k;
        bool front = false;
        if (rayFace(eye, camera.rayDirection(u, v), corners, &front) < shows) {
            c.all += 1 / n;
            c.front += front ? 1 / n : 0;
        }
    }
    return c;
}

BoundingSphere boundingSphere(std::span<const radiosity::Polygon> polygons) {
    BoundingSphere s;
    radiosity::Vec3 lo(1e300), hi(-1e300);
    for (const radiosity::Polygon& p : polygons)
        for (int i = 0; i < p.vertexCount; ++i) {
            lo = glm::min(lo, p.v[static_cast<size_t>(i)]);
            hi = glm::max(hi, p.v[static_cast<size_t>(i)]);
        }
    if (polygons.empty()) return s;
    s.centre = 0.5 * (lo + hi);
    s.radius = 0.5 * glm::length(hi - lo);
    return s;
}

void quickPointGeometry(const radiosity::Scene& scene, const radiosity::Visibility& vis,
                        bool sameScene, const radiosity::ReceiverPoint& at, int rays, uint64_t seed,
                        double* G, double* unoccluded, const BoundingSphere* near) {
    rays = std::clamp(rays, 1, 256);
    const int k = radiosity::strataSide(rays);
    const radiosity::ReceiverPoint p{at.x, at.n, sameScene ? at.polygon : -1};
    for (size_t l = 0; l < scene.lights.size(); ++l) {
        const radiosity::Light& light = scene.lights[l];
        if (light.emitter) {
            // A sun, point lamp or sky: its components from its own sampling.
            const size_t n = static_cast<size_t>(light.emitter->components());
            double out[radiosity::kMaxEmitterComponents] = {};
            radiosity::Rng rng(seed ^ (static_cast<uint64_t>(l) * 0xD1B54A32D192ED03ull));
            light.emitter->unitIrradiance(vis, p, rays, rng, out);
            for (size_t c = 0; c < n && l + c < scene.lights.size(); ++c)
                G[l + c] = out[c] / std::numbers::pi;
            if (unoccluded) {
                light.emitter->unitUnoccluded(p, out);
                for (size_t c = 0; c < n && l + c < scene.lights.size(); ++c)
                    unoccluded[l + c] = out[c] / std::numbers::pi;
            }
            l += std::max<size_t>(n, 1) - 1;
            continue;
        }
        double g = 0, g0 = 0;
        for (const int qi : light.polygons) {
            if (qi == at.polygon) continue;  // an emitting face does not light itself
            const radiosity::Polygon& q = scene.polygons[static_cast<size_t>(qi)];
            const double F =
                radiosity::pointToPolygon(at.x, at.n, q.v.data(), q.vertexCount, q.normal);
            if (!(F > 0)) continue;
            g0 += F;
            if (near && !mayBlock(at.x, boundingSphere({&q, 1}), *near)) {
                g += F;
                continue;
            }
            // Stratified points on q, as DirectLight::geometry draws them.
            radiosity::Rng rng(seed ^ (static_cast<uint64_t>(qi) * 0xD1B54A32D192ED03ull));
            int perm[256];
            radiosity::shuffledStrata(rng, k, perm);
            radiosity::Vec3 from[256], to[256];
            int n = 0;
            for (int i = 0; i < rays; ++i) {
                const double u = ((perm[i] % k) + rng.uniform()) / k;
                const double v = ((perm[i] / k) + rng.uniform()) / k;
                const radiosity::Vec3 y = radiosity::pointOnPolygon(q, u, v);
                if (!(glm::dot(y - at.x, at.n) > 0)) continue;  // below x's horizon
                from[n] = at.x;
                to[n] = y;
                ++n;
            }
            if (n == 0) continue;
            // As DirectLight::geometry: the first minRays decide, the rest only in penumbra.
            int cast = 0;
            const int visible =
                vis.visibleAdaptive(from, to, std::min(n, radiosity::kDefaultMinRays), n, cast,
                                    p.polygon, sameScene ? qi : -1);
            if (cast > 0) g += F * static_cast<double>(visible) / cast;
        }
        G[l] = g;
        if (unoccluded) unoccluded[l] = g0;
    }
}

std::vector<float> quickTransmission(const ItemBuffer& items, const radiosity::Scene& scene,
                                     const radiosity::Visibility& occluder,
                                     const BoundingSphere& near, int rays) {
    const size_t L = scene.lights.size();
    const size_t pixels = static_cast<size_t>(items.width) * static_cast<size_t>(items.height);
    std::vector<float> out(pixels * L, 1.0f);
    // The lamps' faces' spheres, for a first test per pixel without the form factors; a
    // sun, point lamp or sky is measured at every pixel (its extent is its own model's).
    std::vector<BoundingSphere> faces;
    bool everywhere = false;
    for (const radiosity::Light& light : scene.lights) {
        everywhere = everywhere || light.emitter != nullptr;
        for (const int q : light.polygons)
            faces.push_back(boundingSphere({&scene.polygons[static_cast<size_t>(q)], 1}));
    }
    radiosity::parallelForChunks(pixels, 256, [&](size_t first, size_t last) {
        std::vector<double> G(L), G0(L);
        for (size_t px = first; px != last; ++px) {
            const int x = static_cast<int>(px % static_cast<size_t>(items.width));
            const int y = static_cast<int>(px / static_cast<size_t>(items.width));
            const int idx = quickSample(items, scene, x, y);
            if (idx < 0) continue;
            const radiosity::Vec3& point = items.point[static_cast<size_t>(idx)];
            bool reached = everywhere;
            for (size_t f = 0; f < faces.size() && !reached; ++f)
                reached = mayBlock(point, faces[f], near);
            if (!reached) continue;  // no shadow ray of this point can meet the object
            const int p = items.polygon[static_cast<size_t>(idx)];
            const radiosity::ReceiverPoint at{items.point[static_cast<size_t>(idx)],
                                              scene.polygons[static_cast<size_t>(p)].normal, p};
            quickPointGeometry(scene, occluder, /*sameScene=*/false, at, rays,
                               kQuickSeed ^ static_cast<uint64_t>(idx), G.data(), G0.data(), &near);
            for (size_t l = 0; l < L; ++l)
                if (G0[l] > 0) out[px * L + l] = static_cast<float>(std::min(1.0, G[l] / G0[l]));
        }
    });
    return out;
}

}  // namespace relight
