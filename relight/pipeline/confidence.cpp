#include "relight/pipeline/confidence.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace relight {

using radiosity::Rgb;

std::vector<float> vertexConfidence(const VertexDirect& direct, std::span<const Rgb> photoRadiance,
                                    const ConfidenceOptions& options) {
    if (!(options.vFull > options.vLow))
        throw std::invalid_argument("vertexConfidence: vFull must be above vLow");
    const size_t L = static_cast<size_t>(std::max(direct.lights, 0));
    if (L != photoRadiance.size())
        throw std::invalid_argument("vertexConfidence: direct light for " + std::to_string(L) +
                                    " lights, " + std::to_string(photoRadiance.size()) +
                                    " radiances");
    const size_t n = L > 0 ? direct.visible.size() / L : 0;
    std::vector<float> K(n, 0.0f);
    for (size_t v = 0; v < n; ++v) {
        double visible = 0, unoccluded = 0;
        for (size_t l = 0; l < L; ++l) {
            const double E = std::max(photoRadiance[l].maxComponent(), 0.0);
            visible += E * direct.visible[v * L + l];
            unoccluded += E * direct.unoccluded[v * L + l];
        }
        // No lamp of the photo faces the point: its light is indirect only (K = 0).
        const double V = unoccluded > 0 ? std::clamp(visible / unoccluded, 0.0, 1.0) : 0.0;
        K[v] = static_cast<float>(
            std::clamp((V - options.vLow) / (options.vFull - options.vLow), 0.0, 1.0));
    }
    return K;
}

std::vector<Rgb> vertexModelReflectance(const radiosity::LeafMesh& mesh,
                                        const radiosity::Scene& scene, std::span<const int> surface,
                                        std::span<const float> confidence) {
    const size_t nv = mesh.vertices().size();
    if (confidence.size() != nv || surface.size() != scene.polygons.size())
        throw std::invalid_argument("vertexModelReflectance: " + std::to_string(confidence.size()) +
                                    " confidences for " + std::to_string(nv) + " vertices, " +
                                    std::to_string(surface.size()) + " surfaces for " +
                                    std::to_string(scene.polygons.size()) + " polygons");
    // Per surface, sum of K a rho and of K a over its leaves (K: the mean of the leaf's
    // corners), the leaves' reflectances from their texture (relight/pipeline/reflectance.h).
    std::vector<Rgb> sumRho(scene.polygons.size());
    std::vector<double> sumWeight(scene.polygons.size(), 0.0);
    const auto& nodes = mesh.hierarchy().nodes;
    for (size_t n = 0; n < nodes.size(); ++n) {
        const radiosity::Node& e = nodes[n];
        if (e.isCluster() || !e.isLeaf() || e.polygon < 0) continue;
        const auto& c = mesh.corners(static_cast<int>(n));
        double K = 0;
        int corners = 0;
        for (int i = 0; i < 4; ++i) {
            if (c[i] < 0 || (i == 3 && c[3] == c[0])) continue;
            K += static_cast<double>(confidence[static_cast<size_t>(c[i])]);
            ++corners;
        }
        if (corners == 0) continue;
        const double w = K / corners * e.area;
        const size_t s = static_cast<size_t>(surface[static_cast<size_t>(e.polygon)]);
        sumRho[s] += e.rho * w;
        sumWeight[s] += w;
    }
    std::vector<Rgb> rho(nv);
    for (size_t v = 0; v < nv; ++v) {
        const size_t p = static_cast<size_t>(mesh.vertices()[v].polygon);
        const size_t s = static_cast<size_t>(surface[p]);
        // No trusted leaf on the surface: the polygon's own estimate.
        rho[v] = sumWeight[s] > 0 ? sumRho[s] * (1.0 / sumWeight[s]) : scene.polygons[p].rho;
    }
    return rho;
}

}  // namespace relight
