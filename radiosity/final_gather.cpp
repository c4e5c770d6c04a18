#include "radiosity/final_gather.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/hemisphere.h"
#include "radiosity/detail/point_gather.h"
#include "radiosity/detail/rng.h"
#include "radiosity/detail/transfer.h"

namespace radiosity {

using detail::gatherWeights;

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
/// `seed`) hit first: visit(leaf, cell) for each; a ray that leaves the scene visits nothing.
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
        if (leaf >= 0) visit(leaf, cell);
    }
    if (rays) *rays += static_cast<uint64_t>(side) * static_cast<uint64_t>(side);
}

}  // namespace

Rgb rayGatherIndirect(const HierarchicalSolver& solver, int polygon, const Vec3& x, int side,
                      uint64_t seed, uint64_t* rays) {
    const auto& nodes = solver.hierarchy().nodes;
    Rgb sum;
    rayGatherLeaves(solver, polygon, x, side, seed, rays, [&](int leaf, int) {
        const Node& e = nodes[static_cast<size_t>(leaf)];
        sum += e.emitting ? e.B - e.E : e.B;
    });
    side = std::max(side, 1);
    return (1.0 / (side * side)) * sum;
}

void rayGatherResponses(const HierarchicalSolver& solver, const LightResponses& responses,
                        int polygon, const Vec3& x, Rgb* H, int side, uint64_t seed, uint64_t* rays,
                        int32_t* hits) {
    const int L = responses.lights();
    for (int l = 0; l < L; ++l) H[l] = Rgb{};
    if (hits) std::fill_n(hits, std::max(side, 1) * std::max(side, 1), -1);
    rayGatherLeaves(solver, polygon, x, side, seed, rays, [&](int leaf, int cell) {
        if (hits) hits[cell] = leaf;
        // A leaf added after the responses were solved (a virtual object's) has no
        // per-light split: it reflected nothing when they were solved, so it adds nothing.
        if (!responses.covers(leaf)) return;
        const auto r = responses.reflected(leaf);
        for (int l = 0; l < L; ++l) H[l] += r[static_cast<size_t>(l)];
    });
    side = std::max(side, 1);
    for (int l = 0; l < L; ++l) H[l] = (1.0 / (side * side)) * H[l];
}

Rgb finalGatherField(const HierarchicalSolver& solver, std::span<const Rgb> reflected, int polygon,
                     const Vec3& x, int partialRays, uint64_t seed) {
    auto field = [&](int s) {
        return static_cast<size_t>(s) < reflected.size() ? reflected[static_cast<size_t>(s)]
                                                         : Rgb{};
    };
    // A change may be negative: any non-zero component carries.
    auto carries = [&](int s) {
        const Rgb f = field(s);
        return f.r != 0 || f.g != 0 || f.b != 0;
    };
    Rgb H;
    auto acc = [&](int s, double w) { H += field(s) * w; };
    gatherWeights(solver, polygon, x, partialRays, seed, nullptr, carries, acc);
    return H;
}

Rgb rayGatherField(const HierarchicalSolver& solver, std::span<const Rgb> reflected, int polygon,
                   const Vec3& x, int side, uint64_t seed) {
    Rgb sum;
    rayGatherLeaves(solver, polygon, x, side, seed, nullptr, [&](int leaf, int) {
        if (static_cast<size_t>(leaf) < reflected.size())
            sum += reflected[static_cast<size_t>(leaf)];
    });
    side = std::max(side, 1);
    return (1.0 / (side * side)) * sum;
}

namespace {

/// Where the ray o + t d meets the plane of element e (t <= 0: not ahead).
double planeDistance(const Node& e, const Vec3& o, const Vec3& d) {
    const double cosine = glm::dot(e.normal, d);
    return cosine == 0 ? -1.0 : glm::dot(e.normal, e.v[0] - o) / cosine;
}

/// The nearest of `faces` that the ray o + t d meets before tMax: its index, or -1.
int nearestFace(std::span<const int> faces, const Scene& scene, const Vec3& o, const Vec3& d,
                double tMax, double* tHit) {
    int best = -1;
    for (const int f : faces) {
        const Polygon& P = scene.polygons[static_cast<size_t>(f)];
        const double cosine = glm::dot(P.normal, d);
        if (cosine == 0) continue;
        const double t = glm::dot(P.normal, P.v[0] - o) / cosine;
        if (!(t > 0 && t < tMax)) continue;
        const Vec3 y = o + t * d;
        bool inside = true;
        for (int i = 0; i < P.vertexCount && inside; ++i) {
            const Vec3& a = P.v[static_cast<size_t>(i)];
            const Vec3& b = P.v[static_cast<size_t>((i + 1) % P.vertexCount)];
            inside = glm::dot(glm::cross(b - a, y - a), P.normal) >= 0;
        }
        if (inside) {
            best = f;
            tMax = t;
            *tHit = t;
        }
    }
    return best;
}

}  // namespace

Rgb rayGatherField(const HierarchicalSolver& solver, std::span<const Rgb> reflected, int polygon,
                   const Vec3& x, int side, uint64_t seed, std::span<const int32_t> hits,
                   std::span<const int> faces) {
    const auto& h = solver.hierarchy();
    const Scene& scene = solver.scene();
    side = std::max(side, 1);
    const Vec3& n = scene.polygons[static_cast<size_t>(polygon)].normal;
    const Vec3 origin = x + 1e-5 * n;
    const HemisphereFrame frame(n);
    // The generator as rayGatherLeaves seeded it; each cell takes two numbers.
    const uint64_t start = seed * 0x9E3779B97F4A7C15ull + 0x6A7A7ull;
    // The strata whose rays may meet one of the faces: only those are drawn again to test
    // them (a lamp's face fills a small part of the hemisphere).
    thread_local std::vector<StrataWindow> windows;
    windows.clear();
    for (const int f : faces) {
        const Polygon& P = scene.polygons[static_cast<size_t>(f)];
        Vec3 centre{0, 0, 0};
        for (int i = 0; i < P.vertexCount; ++i) centre += P.v[static_cast<size_t>(i)];
        centre /= static_cast<double>(std::max(P.vertexCount, 1));
        double r = 0;
        for (int i = 0; i < P.vertexCount; ++i)
            r = std::max(r, glm::length(P.v[static_cast<size_t>(i)] - centre));
        windows.push_back(StrataWindow::toward(frame, origin, centre, r));
    }
    auto mayMeetFace = [&](size_t cell) {
        return std::any_of(windows.begin(), windows.end(), [&](const StrataWindow& w) {
            return w.mayHold(static_cast<int>(cell), side);
        });
    };
    Rgb sum;
    for (size_t cell = 0; cell < hits.size(); ++cell) {
        int node = hits[cell];
        if (node < 0 || static_cast<size_t>(node) >= h.nodes.size()) continue;
        const bool split = !h.nodes[static_cast<size_t>(node)].isLeaf();
        if (!split && !mayMeetFace(cell)) {
            sum += reflected[static_cast<size_t>(node)];
            continue;
        }
        // The ray again, as rayGatherLeaves drew it, met with its leaf's plane.
        Rng rng(start + 2 * cell * 0x9E3779B97F4A7C15ull);
        const Vec3 d = cosineDirection(frame, static_cast<int>(cell), side, rng);
        const double t = planeDistance(h.nodes[static_cast<size_t>(node)], origin, d);
        if (!(t > 0)) continue;  // grazing: no point of the plane to look up
        double tFace = t;
        const int face = nearestFace(faces, scene, origin, d, t, &tFace);
        if (face >= 0) {
            // A lamp's face put in front of what the ray met: its front sends what it
            // reflects; its back, nothing (surfaces are one-sided).
            if (glm::dot(scene.polygons[static_cast<size_t>(face)].normal, d) < 0)
                node = h.locateLeaf(face, origin + tFace * d);
            else
                continue;
        } else if (split) {
            node = h.locateLeafBelow(node, origin + t * d);
        }
        if (static_cast<size_t>(node) < reflected.size())
            sum += reflected[static_cast<size_t>(node)];
    }
    return (1.0 / (static_cast<double>(side) * side)) * sum;
}

Rgb gatheredIrradiance(const HierarchicalSolver& solver, const DirectLight& direct, int polygon,
                       const Vec3& x, uint64_t seed) {
    return direct.irradiance(polygon, x, seed) + finalGatherIndirect(solver, polygon, x, 4, seed);
}

Rgb gatheredRadiosity(const HierarchicalSolver& solver, const DirectLight& direct, int polygon,
                      const Vec3& x, uint64_t seed) {
    const Scene& scene = solver.scene();
    return scene.emittance(polygon) +
           scene.polygons[polygon].rho * gatheredIrradiance(solver, direct, polygon, x, seed);
}

}  // namespace radiosity
