#include "radiosity/final_gather.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/rng.h"
#include "radiosity/detail/transfer.h"

namespace radiosity {

namespace {

/// Fraction of `count` rays from x to stratified points of node s that arrive.
double pointVisibility(const HierarchicalSolver& solver, int polygon, const Vec3& x, const Vec3& n,
                       int s, int count, Rng& rng, uint64_t& rays) {
    const Hierarchy& h = solver.hierarchy();
    const int k = strataSide(count);
    int perm[64];
    shuffledStrata(rng, k, perm);
    Vec3 from[64], to[64];
    int m = 0;
    for (int i = 0; i < count; ++i) {
        const int cell = perm[i];
        const double u = ((cell % k) + rng.uniform()) / k, v = ((cell / k) + rng.uniform()) / k;
        Vec3 ns;
        const Vec3 y = h.samplePoint(s, u, v, rng.uniform(), &ns);
        // Only mutually facing pairs carry light between one-sided surfaces.
        if (!(glm::dot(y - x, n) > 0) || !(glm::dot(x - y, ns) > 0)) continue;
        from[m] = x;
        to[m] = y;
        ++m;
    }
    if (m == 0) return 0.0;
    const int polyS = h.nodes[s].isCluster() ? -1 : h.nodes[s].polygon;
    const int visible = solver.visibility().visibleBatch(from, to, m, nullptr, polygon, polyS);
    rays += static_cast<uint64_t>(m);
    return static_cast<double>(visible) / m;
}

/// What an element source sends to x: B_s F(x), where F = F(x -> s) is given. Where x is
/// close to s (F above kDescendF) the source's own subdivision is used instead: the sum
/// over its children of B_c F(x -> c). A link is accepted for the receiver element as a
/// whole (its mean F is small), yet a point of it near the source's edge can see the
/// source at a large angle, and there the source's mean B is wrong: a wall that is bright
/// near a corner and dark elsewhere would light the corner with its mean.
constexpr double kDescendF = 0.05;

template <class Accumulate>
void elementWeights(const Hierarchy& h, const Vec3& x, const Vec3& n, int s, double F, double V,
                    Accumulate& acc) {
    const Node& S = h.nodes[s];
    if (S.isLeaf() || !(F > kDescendF)) {
        acc(s, F * V);
        return;
    }
    for (int k = 0; k < S.childCount; ++k) {
        const Node& C = h.nodes[S.firstChild + k];
        const double Fc = pointToPolygon(x, n, C.v.data(), C.vertexCount, C.normal);
        if (Fc > 0) elementWeights(h, x, n, S.firstChild + k, Fc, V, acc);
    }
}

/// Smallest F(x) for which a PARTIAL link's visibility is measured from x. Below it the
/// link's own V (its mean over the receiving element) is kept: the term can then move the
/// gather by less than kPointVisibilityF times the source's radiosity, and a finely cut
/// rough wall has hundreds of such links per point, whose rays made nine tenths of its
/// vertex lighting's time.
constexpr double kPointVisibilityF = 1e-3;

/// The final gather's traversal: for every link on the chain above the leaf holding x
/// whose source `carries(source)`, calls acc(node, w) with the weight w = F(x) V(x) by
/// which the radiosity that `node` reflects reaches x (F per point; element sources
/// descend into their children near x; V measured from x on PARTIAL links).
template <class Carries, class Accumulate>
void gatherWeights(const HierarchicalSolver& solver, int polygon, const Vec3& x, int partialRays,
                   uint64_t seed, uint64_t* rays, const Carries& carries, Accumulate& acc) {
    const Hierarchy& h = solver.hierarchy();
    const Vec3& n = solver.scene().polygons[polygon].normal;
    partialRays = std::clamp(partialRays, 0, 64);
    Rng rng(seed * 0xD1B54A32D192ED03ull + 0x51ED27ull);
    uint64_t cast = 0;
    for (int node = h.locateLeaf(polygon, x); node >= 0; node = h.nodes[node].parent) {
        for (const Link& l : solver.linksOf(node)) {
            const Node& S = h.nodes[l.source];
            if (!(l.V > 0) && l.type != VisibilityType::partial) continue;
            if (!carries(l.source)) continue;
            double F;
            if (!S.isCluster()) {
                F = pointToPolygon(x, n, S.v.data(), S.vertexCount, S.normal);
            } else {
                F = pointToNode(x, n, S);  // the link's own bounded estimate, from x
            }
            if (!(F > 0)) continue;
            const double V =
                l.type == VisibilityType::partial && partialRays > 0 && F > kPointVisibilityF
                    ? pointVisibility(solver, polygon, x, n, l.source, partialRays, rng, cast)
                    : static_cast<double>(l.V);
            if (!(V > 0)) continue;
            if (S.isCluster())
                acc(l.source, F * V);
            else
                elementWeights(h, x, n, l.source, F, V, acc);
        }
    }
    if (rays) *rays += cast;
}

}  // namespace

Rgb finalGatherIndirect(const HierarchicalSolver& solver, int polygon, const Vec3& x,
                        int partialRays, uint64_t seed, uint64_t* rays) {
    const auto& nodes = solver.hierarchy().nodes;
    // An emitter's own emission is direct light (DirectLight); what it reflects, if
    // anything, is indirect.
    auto reflected = [&](int s) {
        return nodes[s].emitting ? nodes[s].B - nodes[s].E : nodes[s].B;
    };
    auto carries = [&](int s) { return reflected(s).maxComponent() > 0; };
    Rgb H;
    auto acc = [&](int s, double w) { H += reflected(s) * w; };
    gatherWeights(solver, polygon, x, partialRays, seed, rays, carries, acc);
    return H;
}

std::vector<GatherWeight> finalGatherWeights(const HierarchicalSolver& solver, int polygon,
                                             const Vec3& x, int partialRays, uint64_t seed,
                                             uint64_t* rays) {
    std::vector<GatherWeight> out;
    auto carries = [](int) { return true; };
    auto acc = [&](int s, double w) { out.push_back({s, static_cast<float>(w)}); };
    gatherWeights(solver, polygon, x, partialRays, seed, rays, carries, acc);
    return out;
}

void finalGatherResponses(const HierarchicalSolver& solver, const LightResponses& responses,
                          int polygon, const Vec3& x, Rgb* H, int partialRays, uint64_t seed,
                          uint64_t* rays) {
    const int L = responses.lights();
    for (int l = 0; l < L; ++l) H[l] = Rgb{};
    auto carries = [&](int s) {
        for (const Rgb& r : responses.reflected(s))
            if (r.maxComponent() > 0) return true;
        return false;
    };
    auto acc = [&](int s, double w) {
        const auto r = responses.reflected(s);
        for (int l = 0; l < L; ++l) H[l] += r[l] * w;
    };
    gatherWeights(solver, polygon, x, partialRays, seed, rays, carries, acc);
}

namespace {

/// The leaves that side^2 cosine-distributed rays from x (stratified, jittered, seeded by
/// `seed`) hit first: visit(leaf) for each; a ray that leaves the scene visits nothing.
template <class Visit>
void rayGatherLeaves(const HierarchicalSolver& solver, int polygon, const Vec3& x, int side,
                     uint64_t seed, uint64_t* rays, const Visit& visit) {
    const Scene& scene = solver.scene();
    const Vec3& n = scene.polygons[static_cast<size_t>(polygon)].normal;
    // Off the surface by a hair, so that the rays do not find the polygon they leave.
    const Vec3 origin = x + 1e-5 * n;
    const HemisphereFrame frame(n);
    Rng rng(seed * 0x9E3779B97F4A7C15ull + 0x6A7A7ull);
    side = std::max(side, 1);
    for (int cell = 0; cell < side * side; ++cell) {
        const Vec3 d = cosineDirection(frame, cell, side, rng);
        // Surfaces are one-sided: the back of a polygon sends nothing (but a thin part's
        // other face, back to back with it, does: intersectFront).
        const FrontHit found = intersectFront(solver.visibility(), scene, origin, d, 1e-6);
        if (!found.front) continue;
        const Visibility::Hit& hit = found.hit;
        const int leaf = solver.hierarchy().locateLeaf(hit.polygon, origin + hit.t * d);
        if (leaf >= 0) visit(leaf);
    }
    if (rays) *rays += static_cast<uint64_t>(side) * static_cast<uint64_t>(side);
}

}  // namespace

Rgb rayGatherIndirect(const HierarchicalSolver& solver, int polygon, const Vec3& x, int side,
                      uint64_t seed, uint64_t* rays) {
    const auto& nodes = solver.hierarchy().nodes;
    Rgb sum;
    rayGatherLeaves(solver, polygon, x, side, seed, rays, [&](int leaf) {
        const Node& e = nodes[static_cast<size_t>(leaf)];
        sum += e.emitting ? e.B - e.E : e.B;
    });
    side = std::max(side, 1);
    return (1.0 / (side * side)) * sum;
}

void rayGatherResponses(const HierarchicalSolver& solver, const LightResponses& responses,
                        int polygon, const Vec3& x, Rgb* H, int side, uint64_t seed,
                        uint64_t* rays) {
    const int L = responses.lights();
    for (int l = 0; l < L; ++l) H[l] = Rgb{};
    rayGatherLeaves(solver, polygon, x, side, seed, rays, [&](int leaf) {
        const auto r = responses.reflected(leaf);
        for (int l = 0; l < L; ++l) H[l] += r[static_cast<size_t>(l)];
    });
    side = std::max(side, 1);
    for (int l = 0; l < L; ++l) H[l] = (1.0 / (side * side)) * H[l];
}

Rgb gatheredIrradiance(const HierarchicalSolver& solver, const DirectLight& direct, int polygon,
                       const Vec3& x, uint64_t seed) {
    const Scene& scene = solver.scene();
    double G[64];
    std::vector<double> Gheap;
    double* g = G;
    if (scene.lights.size() > 64) {
        Gheap.resize(scene.lights.size());
        g = Gheap.data();
    }
    direct.geometry(polygon, x, seed, g);
    Rgb H = finalGatherIndirect(solver, polygon, x, 4, seed);
    for (size_t l = 0; l < scene.lights.size(); ++l) H += scene.lights[l].emittance() * g[l];
    return H;
}

Rgb gatheredRadiosity(const HierarchicalSolver& solver, const DirectLight& direct, int polygon,
                      const Vec3& x, uint64_t seed) {
    const Scene& scene = solver.scene();
    return scene.emittance(polygon) +
           scene.polygons[polygon].rho * gatheredIrradiance(solver, direct, polygon, x, seed);
}

}  // namespace radiosity
