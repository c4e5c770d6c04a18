// The solver's lights that are not emitting faces (radiosity/emitter.h): their direct
// light per leaf element (Hx), which gather/push-pull then carries as indirect light.
#include <algorithm>
#include <stdexcept>

#include "radiosity/detail/rng.h"
#include "radiosity/parallel.h"
#include "radiosity/solver.h"

namespace radiosity {

int HierarchicalSolver::addEmitter(std::unique_ptr<Emitter> emitter) {
    if (!emitter) throw std::invalid_argument("addEmitter: no emitter");
    emitters_.push_back(std::move(emitter));
    updateDirectIrradiance(/*all=*/true);
    return static_cast<int>(emitters_.size()) - 1;
}

void HierarchicalSolver::editEmitter(int i, const EmitterEdit& edit) {
    emitters_.at(static_cast<size_t>(i))->apply(edit);
    updateDirectIrradiance(/*all=*/true);
    if (started_) gatherPushPull();
}

void HierarchicalSolver::updateDirectIrradiance(bool all) {
    std::vector<int> leaves;
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        const Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        if (all || !e.HxMeasured) leaves.push_back(static_cast<int>(n));
    }
    const int side = strataSide(std::max(options_.directPoints, 1));
    const bool any =
        std::any_of(emitters_.begin(), emitters_.end(), [](const auto& e) { return e->on(); });
    parallelFor(leaves.size(), 16, [&](size_t i) {
        Node& e = h_.nodes[leaves[i]];
        e.HxMeasured = true;
        e.Hx = Rgb{};
        if (!any || !(e.rho.maxComponent() > 0)) return;  // a lamp's face reflects nothing
        // The mean over stratified points of the element: the sun's and the sky's light
        // changes across a leaf at a shadow's edge, which one point would miss.
        Rng rng(0x6a09e667f3bcc908ull ^ static_cast<uint64_t>(leaves[i]));
        Rgb sum;
        for (int cell = 0; cell < side * side; ++cell) {
            const double u = ((cell % side) + rng.uniform()) / side;
            const double v = ((cell / side) + rng.uniform()) / side;
            const ReceiverPoint p{pointOnElement(e, u, v), e.normal, e.polygon};
            sum += totalIrradiance(emitters_, *vis_, p, options_.directRays, rng.next());
        }
        e.Hx = sum * (1.0 / (side * side));
    });
    directPower_ = Rgb{};
    for (const Node& e : h_.nodes)
        if (!e.isCluster() && e.isLeaf()) directPower_ += e.Hx * e.area;
}

double HierarchicalSolver::sourcePower() const {
    return (scene_.emittedPower() + directPower_).maxComponent();
}

}  // namespace radiosity
