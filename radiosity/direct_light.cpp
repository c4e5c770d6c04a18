#include "radiosity/direct_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/rng.h"

namespace radiosity {

DirectLight::DirectLight(const HierarchicalSolver& solver, DirectLightOptions options)
    : solver_(solver), options_(options) {
    options_.minRays = std::clamp(options_.minRays, 1, 256);
    options_.maxRays = std::clamp(options_.maxRays, options_.minRays, 256);
    const Scene& scene = solver.scene();
    lightSlot_.assign(scene.polygons.size(), -1);
    for (const Light& l : scene.lights)
        for (int q : l.polygons) lightSlot_[static_cast<size_t>(q)] = lightPolygons_++;
    // One byte per node and light polygon: a room's few lamps cost a few bytes per node; a
    // lamp made of thousands of faces goes without the memo rather than take gigabytes.
    constexpr size_t kMaxShaftMemo = size_t{1} << 26;
    const size_t entries = solver.hierarchy().nodes.size() * static_cast<size_t>(lightPolygons_);
    if (entries > 0 && entries <= kMaxShaftMemo)
        shaftMemo_.reset(new std::atomic<uint8_t>[entries]());  // () : all 0, not yet known
}

bool DirectLight::shaftClear(int leaf, int q) const {
    const int slot = lightSlot_[static_cast<size_t>(q)];
    if (!shaftMemo_ || slot < 0) return shaftClearByLinks(leaf, q);
    // Threads that race on an entry compute the same verdict: relaxed order suffices.
    std::atomic<uint8_t>& m =
        shaftMemo_[static_cast<size_t>(leaf) * static_cast<size_t>(lightPolygons_) +
                   static_cast<size_t>(slot)];
    const uint8_t known = m.load(std::memory_order_relaxed);
    if (known != 0) return known == 1;
    const bool clear = shaftClearByLinks(leaf, q);
    m.store(clear ? 1 : 2, std::memory_order_relaxed);
    return clear;
}

bool DirectLight::shaftClearByLinks(int leaf, int q) const {
    const Hierarchy& h = solver_.hierarchy();
    bool found = false;
    for (int n = leaf; n >= 0; n = h.nodes[n].parent) {
        for (const Link& l : solver_.linksOf(n)) {
            const Node& S = h.nodes[l.source];
            if (S.isCluster() || S.polygon != q) continue;
            if (!l.shaftEmpty) return false;
            found = true;
        }
    }
    return found;
}

size_t DirectLight::emitterGeometry(size_t l, int polygon, const Vec3& x, uint64_t base, double* G,
                                    double* unoccluded) const {
    // All components of the emitter from the same rays (a sky's 9 coefficients share its
    // directions: the transfer vector); G is per unit radiance, H = pi L G, so the unit
    // irradiance is divided by pi.
    const Scene& scene = solver_.scene();
    const Emitter& e = *scene.lights[l].emitter;
    const size_t n = std::min(static_cast<size_t>(e.components()), scene.lights.size() - l);
    const ReceiverPoint p{x, scene.polygons[polygon].normal, polygon};
    double out[kMaxEmitterComponents] = {};
    Rng rng(Rng(base ^ (static_cast<uint64_t>(l + 1) * 0xA0761D6478BD642Full)).next());
    e.unitIrradiance(solver_.visibility(), p, options_.maxRays, rng, out);
    for (size_t c = 0; c < n; ++c) G[l + c] = out[c] / std::numbers::pi;
    if (unoccluded) {
        e.unitUnoccluded(p, out);
        for (size_t c = 0; c < n; ++c) unoccluded[l + c] = out[c] / std::numbers::pi;
    }
    return std::max<size_t>(n, 1);
}

Rgb DirectLight::irradiance(int polygon, const Vec3& x, uint64_t seed) const {
    const Scene& scene = solver_.scene();
    double G[64];  // on the stack for the usual few lights
    std::vector<double> Gheap;
    double* g = G;
    if (scene.lights.size() > 64) {
        Gheap.resize(scene.lights.size());
        g = Gheap.data();
    }
    geometry(polygon, x, seed, g);
    Rgb H;
    for (size_t l = 0; l < scene.lights.size(); ++l) H += scene.lights[l].emittance() * g[l];
    return H;
}

void DirectLight::geometry(int polygon, const Vec3& x, uint64_t seed, double* G, double* unoccluded,
                           int firstLight) const {
    const Scene& scene = solver_.scene();
    const Polygon& p = scene.polygons[polygon];
    // The leaf is for the quads' shafts only: a sun's or a sky's samples (the per-pixel
    // light of a moved sun: 1.2 M samples at 320 x 240) need not locate it.
    int leaf = -2;
    const uint64_t base = seed * 0x9E3779B97F4A7C15ull + 0x1234567ull;
    const int maxRays = options_.maxRays;
    const int k = strataSide(maxRays);
    uint64_t rays = 0;
    for (size_t l = static_cast<size_t>(std::max(firstLight, 0)); l < scene.lights.size(); ++l) {
        if (scene.lights[l].emitter) {
            l += emitterGeometry(l, polygon, x, base, G, unoccluded) - 1;
            continue;
        }
        double g = 0, g0 = 0;
        for (int qi : scene.lights[l].polygons) {
            if (qi == polygon) continue;  // an emitting face does not light itself
            const Polygon& q = scene.polygons[qi];
            const double F = pointToPolygon(x, p.normal, q.v.data(), q.vertexCount, q.normal);
            if (!(F > 0)) continue;
            g0 += F;
            if (leaf == -2) leaf = solver_.hierarchy().locateLeaf(polygon, x);
            if (shaftClear(leaf, qi)) {
                g += F;
                continue;
            }
            // The rays toward q from a stream of their own: which polygons before q had a
            // clear shaft (it changes as links are refined, or cut by a virtual object)
            // does not change them, so a point gets the same rays in every state of the
            // solver where it needs them.
            Rng rng(Rng(base ^ (static_cast<uint64_t>(qi) * 0xD1B54A32D192ED03ull)).next());
            // Stratified points on q, strata in random order so that any prefix of the
            // set covers q uniformly: the first minRays decide, the rest follow in
            // penumbra. Only points above x's horizon carry light (F is clipped the same
            // way), so the others are not counted.
            int perm[256];
            shuffledStrata(rng, k, perm);
            Vec3 from[256], to[256];
            int n = 0;
            for (int i = 0; i < maxRays; ++i) {
                const double u = ((perm[i] % k) + rng.uniform()) / k;
                const double v = ((perm[i] / k) + rng.uniform()) / k;
                const Vec3 y = pointOnPolygon(q, u, v);
                if (!(glm::dot(y - x, p.normal) > 0)) continue;
                from[n] = x;
                to[n] = y;
                ++n;
            }
            if (n == 0) continue;
            int cast = 0;
            const int visible = solver_.visibility().visibleAdaptive(from, to, options_.minRays, n,
                                                                     cast, polygon, qi);
            rays += static_cast<uint64_t>(cast);
            g += F * static_cast<double>(visible) / cast;
        }
        G[l] = g;
        if (unoccluded) unoccluded[l] = g0;
    }
    rays_.fetch_add(rays, std::memory_order_relaxed);
}

}  // namespace radiosity
