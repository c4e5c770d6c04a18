#include "relight/pipeline/vertex_lighting.h"

#include <atomic>
#include <numbers>
#include <span>

#include "radiosity/final_gather.h"
#include "radiosity/parallel.h"

namespace relight {

using radiosity::Rgb;

Rgb VertexLighting::irradiance(int v, std::span<const Rgb> radiance) const {
    Rgb H;
    const Rgb* h = response.data() + static_cast<size_t>(v) * lights;
    for (int l = 0; l < lights; ++l) H += radiance[l] * h[l];
    return H;
}

namespace {

/// An empty lighting of `mesh`'s vertices for the lights of `responses`.
VertexLighting emptyLighting(const radiosity::LeafMesh& mesh,
                             const radiosity::LightResponses& responses) {
    VertexLighting out;
    out.lights = responses.lights();
    out.response.assign(mesh.vertices().size() * static_cast<size_t>(out.lights), Rgb{});
    return out;
}

}  // namespace

VertexLighting measureVertexLighting(const radiosity::HierarchicalSolver& solver,
                                     const radiosity::LeafMesh& mesh,
                                     const radiosity::LightResponses& responses,
                                     radiosity::DirectLightOptions options, VertexDirect& direct,
                                     const radiosity::ProgressFn& progress,
                                     radiosity::Clock::time_point gatherRaysUntil) {
    const radiosity::DirectLight light(solver, options);
    VertexLighting out = emptyLighting(mesh, responses);
    const int L = out.lights;
    const int n = static_cast<int>(mesh.vertices().size());
    direct.lights = L;
    direct.visible.assign(static_cast<size_t>(n) * L, 0.0);
    direct.unoccluded.assign(static_cast<size_t>(n) * L, 0.0);
    if (L == 0) return out;
    // The indirect light: one final gather of every vertex, far links shared per element.
    std::vector<radiosity::GatherPoint> points(static_cast<size_t>(n));
    for (int v = 0; v < n; ++v) {
        const int p = mesh.vertices()[v].polygon;
        // A light's own emitting face is shown with the light's radiance, not lit.
        if (solver.scene().polygons[p].light >= 0) continue;
        points[v] = {p, mesh.insidePoint(v), static_cast<uint64_t>(v)};
    }
    direct.gather = radiosity::sharedFinalGather(solver, points, 4, progress, gatherRaysUntil);
    direct.gather.addResponses(responses, out.response.data());
    radiosity::ProgressMeter meter(progress, "direct light at the vertices",
                                   static_cast<size_t>(n));
    radiosity::parallelForChunks(static_cast<size_t>(n), 64, [&](size_t first, size_t last) {
        meter.add(last - first);
        std::vector<double> G(static_cast<size_t>(L)), G0(static_cast<size_t>(L));
        for (int v = static_cast<int>(first); v != static_cast<int>(last); ++v) {
            const int p = points[v].polygon;
            if (p < 0) continue;
            Rgb* h = out.response.data() + static_cast<size_t>(v) * L;
            const size_t at = static_cast<size_t>(v) * L;
            light.geometry(p, points[v].x, static_cast<uint64_t>(v), G.data(), G0.data());
            for (int l = 0; l < L; ++l) {
                h[l] += Rgb::gray(std::numbers::pi * G[l]);
                direct.visible[at + l] = std::numbers::pi * G[l];
                direct.unoccluded[at + l] = std::numbers::pi * G0[l];
            }
        }
    });
    out.rays = direct.gather.rays + light.raysCast();
    return out;
}

VertexLighting regatherVertexLighting(const radiosity::HierarchicalSolver& solver,
                                      const radiosity::LeafMesh& mesh,
                                      const radiosity::LightResponses& responses,
                                      const VertexDirect& direct,
                                      std::span<const Rgb> directScale) {
    VertexLighting out = emptyLighting(mesh, responses);
    const int L = out.lights;
    const int n = static_cast<int>(mesh.vertices().size());
    if (L == 0) return out;
    const bool useTerms = direct.gather.points() == static_cast<size_t>(n);
    if (useTerms) direct.gather.addResponses(responses, out.response.data());
    std::atomic<uint64_t> gatherRays{0};
    radiosity::parallelForChunks(static_cast<size_t>(n), 64, [&](size_t from, size_t to) {
        uint64_t rays = 0;
        for (int v = static_cast<int>(from); v != static_cast<int>(to); ++v) {
            const int p = mesh.vertices()[v].polygon;
            if (solver.scene().polygons[p].light >= 0) continue;  // shown, not lit
            Rgb* h = out.response.data() + static_cast<size_t>(v) * L;
            if (!useTerms)
                radiosity::finalGatherResponses(solver, responses, p, mesh.insidePoint(v), h, 4,
                                                static_cast<uint64_t>(v), &rays);
            const Rgb c = directScale.empty() ? Rgb::gray(1.0) : directScale[v];
            const size_t at = static_cast<size_t>(v) * L;
            for (int l = 0; l < L; ++l) h[l] += c * direct.visible[at + l];
        }
        gatherRays += rays;
    });
    out.rays = gatherRays.load();
    return out;
}

}  // namespace relight
