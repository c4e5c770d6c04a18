#include "relight/pipeline/vertex_lighting.h"

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
    // The gather's terms: made with the direct light, reused by later calls.
    std::vector<std::vector<radiosity::GatherWeight>> terms(directOut ? n : 0);
    const bool useTerms = given && given->termStart.size() == static_cast<size_t>(n) + 1;
    tbb::parallel_for(tbb::blocked_range<int>(0, n, 64), [&](const tbb::blocked_range<int>& r) {
        std::vector<double> G(static_cast<size_t>(L)), G0(static_cast<size_t>(L));
        uint64_t rays = 0;
        for (int v = r.begin(); v != r.end(); ++v) {
            const int p = mesh.vertices()[v].polygon;
            // A light's own emitting face is shown with the light's radiance, not lit.
            if (solver.scene().polygons[p].light >= 0) continue;
            const radiosity::Vec3 x = mesh.insidePoint(v);
            Rgb* h = out.response.data() + static_cast<size_t>(v) * L;
            if (useTerms) {
                for (size_t t = given->termStart[v]; t < given->termStart[v + 1]; ++t) {
                    const radiosity::GatherWeight& g = given->terms[t];
                    const auto R = responses.reflected(g.node);
                    for (int l = 0; l < L; ++l) h[l] += R[l] * g.w;
                }
            } else if (directOut) {
                terms[v] =
                    radiosity::finalGatherWeights(solver, p, x, 4, static_cast<uint64_t>(v), &rays);
                for (const radiosity::GatherWeight& g : terms[v]) {
                    const auto R = responses.reflected(g.node);
                    for (int l = 0; l < L; ++l) h[l] += R[l] * g.w;
                }
            } else {
                radiosity::finalGatherResponses(solver, responses, p, x, h, 4,
                                                static_cast<uint64_t>(v), &rays);
            }
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
    if (directOut) {
        directOut->termStart.assign(static_cast<size_t>(n) + 1, 0);
        for (int v = 0; v < n; ++v)
            directOut->termStart[v + 1] = directOut->termStart[v] + terms[v].size();
        directOut->terms.clear();
        directOut->terms.reserve(directOut->termStart[n]);
        for (auto& t : terms) {
            directOut->terms.insert(directOut->terms.end(), t.begin(), t.end());
            t = {};
        }
    }
    out.rays = gatherRays.load() + direct.raysCast();
    return out;
}

}  // namespace relight
