#include "radiosity/light_response.h"

namespace radiosity {

LightResponses::LightResponses(HierarchicalSolver& solver)
    : lights_(static_cast<int>(solver.scene().lights.size())) {
    const auto& nodes = solver.hierarchy().nodes;
    std::vector<Rgb> original(lights_);
    for (int l = 0; l < lights_; ++l) original[l] = solver.scene().lights[l].radiance;
    // First every light on at unit radiance: links for lights that had none are refined
    // with all lights contributing to the power threshold, as a solve with them on would.
    std::vector<Rgb> unit(lights_, Rgb::gray(1.0));
    solver.setLightRadiances(unit);
    R_.assign(nodes.size() * lights_, Rgb{});
    for (int l = 0; l < lights_; ++l) {
        std::vector<Rgb> alone(lights_);
        alone[l] = Rgb::gray(1.0);
        solver.setLightRadiances(alone);
        // setLightRadiances may have added nodes only while adding links (above, not
        // here): the node count is fixed from now on.
        for (size_t n = 0; n < nodes.size(); ++n) {
            const Node& e = nodes[n];
            R_[n * lights_ + l] = e.emitting ? e.B - e.E : e.B;
        }
    }
    solver.setLightRadiances(original);
}

Rgb LightResponses::reflected(int node, std::span<const Rgb> radiance) const {
    Rgb sum;
    const auto r = reflected(node);
    for (int l = 0; l < lights_; ++l) sum += radiance[l] * r[l];
    return sum;
}

}  // namespace radiosity
