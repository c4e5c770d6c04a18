#include "relight/vertex_lighting.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <numbers>

#include "radiosity/final_gather.h"

namespace relight {

using radiosity::Rgb;

Rgb VertexLighting::irradiance(int v, std::span<const Rgb> radiance) const {
    Rgb H;
    const Rgb* h = response.data() + static_cast<size_t>(v) * lights;
    for (int l = 0; l < lights; ++l) H += radiance[l] * h[l];
    return H;
}

VertexLighting computeVertexLighting(const radiosity::HierarchicalSolver& solver,
                                     const radiosity::LeafMesh& mesh,
                                     const radiosity::LightResponses& responses,
                                     radiosity::DirectLightOptions options, VertexDirect* directOut,
                                     const VertexDirect* given,
                                     const std::vector<Rgb>* directScale) {
    const radiosity::DirectLight direct(solver, options);
    VertexLighting out;
    out.lights = responses.lights();
    const int L = out.lights;
    const int n = static_cast<int>(mesh.vertices().size());
    out.response.assign(static_cast<size_t>(n) * L, Rgb{});
    if (directOut) {
        directOut->lights = L;
        directOut->visible.assign(static_cast<size_t>(n) * L, 0.0);
        directOut->unoccluded.assign(static_cast<size_t>(n) * L, 0.0);
    }
    if (L == 0) return out;
    std::atomic<uint64_t> gatherRays{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 64), [&](const tbb::blocked_range<int>& r) {
        std::vector<double> G(static_cast<size_t>(L)), G0(static_cast<size_t>(L));
        uint64_t rays = 0;
        for (int v = r.begin(); v != r.end(); ++v) {
            const int p = mesh.vertices()[v].polygon;
            // A light's own emitting face is shown with the light's radiance, not lit.
            if (solver.scene().polygons[p].light >= 0) continue;
            const radiosity::Vec3 x = mesh.insidePoint(v);
            Rgb* h = out.response.data() + static_cast<size_t>(v) * L;
            radiosity::finalGatherResponses(solver, responses, p, x, h, 4, static_cast<uint64_t>(v),
                                            &rays);
            const size_t at = static_cast<size_t>(v) * L;
            if (given) {
                const Rgb c =
                    directScale && !directScale->empty() ? (*directScale)[v] : Rgb::gray(1.0);
                for (int l = 0; l < L; ++l) h[l] += c * given->visible[at + l];
                continue;
            }
            direct.geometry(p, x, static_cast<uint64_t>(v), G.data(), G0.data());
            for (int l = 0; l < L; ++l) {
                h[l] += Rgb::gray(std::numbers::pi * G[l]);
                if (directOut) {
                    directOut->visible[at + l] = std::numbers::pi * G[l];
                    directOut->unoccluded[at + l] = std::numbers::pi * G0[l];
                }
            }
        }
        gatherRays += rays;
    });
    out.rays = gatherRays.load() + direct.raysCast();
    return out;
}

}  // namespace relight
