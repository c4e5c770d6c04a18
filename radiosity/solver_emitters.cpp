// The solver's lights that are not emitting faces (radiosity/emitter.h): their direct
// light per leaf element (Hx), which gather/push-pull then carries as indirect light.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "radiosity/detail/rng.h"
#include "radiosity/parallel.h"
#include "radiosity/solver.h"

namespace radiosity {

int HierarchicalSolver::addEmitter(std::shared_ptr<const Emitter> emitter) {
    if (!emitter) throw std::invalid_argument("addEmitter: no emitter");
    const int first = static_cast<int>(scene_.lights.size());
    const std::vector<Rgb> s = emitter->strengths();
    for (int c = 0; c < emitter->components(); ++c) {
        Light l;
        l.name = emitter->name();
        l.radiance = s.at(static_cast<size_t>(c));
        l.emitter = emitter;
        l.component = c;
        scene_.lights.push_back(std::move(l));
    }
    updateDirectIrradiance(/*all=*/true);  // the layout of Hunit_ changed
    return first;
}

void HierarchicalSolver::removeEmitterLights(int first) {
    if (first < 0 || static_cast<size_t>(first) > scene_.lights.size())
        throw std::invalid_argument("removeEmitterLights: no light " + std::to_string(first));
    for (size_t l = static_cast<size_t>(first); l < scene_.lights.size(); ++l)
        if (!scene_.lights[l].emitter)
            throw std::invalid_argument("removeEmitterLights: light '" + scene_.lights[l].name +
                                        "' is faces");
    scene_.lights.resize(static_cast<size_t>(first));
    updateDirectIrradiance(/*all=*/true);
    if (started_) gatherPushPull();
}

HierarchicalSolver::LightState HierarchicalSolver::lightState() const {
    LightState s;
    s.nodes.reserve(h_.nodes.size());
    for (const Node& n : h_.nodes) s.nodes.push_back({n.B, n.Bsent, n.H, n.Hd, n.Hx});
    s.Hv.reserve(h_.clusterFields.size());
    for (const ClusterFields& c : h_.clusterFields) s.Hv.push_back(c.Hv);
    for (const Light& l : scene_.lights) s.radiance.push_back(l.radiance);
    return s;
}

void HierarchicalSolver::restoreLightState(const LightState& state) {
    if (state.nodes.size() != h_.nodes.size() || state.Hv.size() != h_.clusterFields.size() ||
        state.radiance.size() != scene_.lights.size())
        throw std::logic_error("restoreLightState: the solver's nodes or lights changed since");
    for (size_t l = 0; l < state.radiance.size(); ++l)
        scene_.lights[l].radiance = state.radiance[l];
    h_.updateEmittance(scene_);
    sumDirectIrradiance();  // the emitters' power at these radiances
    for (size_t i = 0; i < h_.nodes.size(); ++i) {
        Node& n = h_.nodes[i];
        const LightState::NodeLight& b = state.nodes[i];
        n.B = b.B;
        n.Bsent = b.Bsent;
        n.H = b.H;
        n.Hd = b.Hd;
        n.Hx = b.Hx;
    }
    for (size_t c = 0; c < state.Hv.size(); ++c) h_.clusterFields[c].Hv = state.Hv[c];
}

void HierarchicalSolver::editEmitter(int light, const EmitterEdit& edit) {
    const Light& l = scene_.lights.at(static_cast<size_t>(light));
    if (!l.emitter) throw std::invalid_argument("editEmitter: light '" + l.name + "' is faces");
    const int first = light - l.component;
    std::unique_ptr<Emitter> e = l.emitter->clone();
    std::vector<Rgb> s(static_cast<size_t>(e->components()));
    for (size_t c = 0; c < s.size(); ++c) s[c] = scene_.lights[first + c].radiance;
    e->setStrengths(s);
    e->apply(edit);
    setLightEmitter(first, std::move(e));
}

void HierarchicalSolver::setLightEmitter(int light, std::shared_ptr<const Emitter> emitter) {
    const Light& l = scene_.lights.at(static_cast<size_t>(light));
    if (!l.emitter || !emitter || emitter->components() != l.emitter->components())
        throw std::invalid_argument("setLightEmitter: light '" + l.name +
                                    "' needs an emitter of as many components");
    const size_t first = static_cast<size_t>(light - l.component);
    const std::vector<Rgb> s = emitter->strengths();
    for (size_t c = 0; c < s.size(); ++c) {
        scene_.lights[first + c].emitter = emitter;
        scene_.lights[first + c].radiance = s[c];
    }
    updateDirectIrradiance(/*all=*/true);
    if (started_) gatherPushPull();
}

void HierarchicalSolver::updateDirectIrradiance(bool all) {
    // The scene's lights with an emitter (given with the scene, or added): when they
    // change, so does the layout of Hunit_.
    std::vector<int> now;
    for (size_t l = 0; l < scene_.lights.size(); ++l)
        if (scene_.lights[l].emitter) now.push_back(static_cast<int>(l));
    if (now != emitterLights_) {
        emitterLights_ = std::move(now);
        Hunit_.clear();
        all = true;
    }
    const size_t J = emitterLights_.size();
    if (J == 0) {
        sumDirectIrradiance();  // the last emitter removed: its light leaves the leaves too
        return;
    }
    Hunit_.resize(h_.nodes.size() * J, 0.0);
    std::vector<int> leaves;
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        const Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        if (all || !e.HxMeasured) leaves.push_back(static_cast<int>(n));
    }
    const int side = strataSide(std::max(options_.directPoints, 1));
    parallelFor(leaves.size(), 16, [&](size_t i) {
        Node& e = h_.nodes[leaves[i]];
        e.HxMeasured = true;
        double* H = Hunit_.data() + static_cast<size_t>(leaves[i]) * J;
        std::fill(H, H + J, 0.0);
        if (!(e.rho.maxComponent() > 0)) return;  // a lamp's face reflects nothing
        // The mean over stratified points of the element: the sun's and the sky's light
        // changes across a leaf at a shadow's edge, which one point would miss.
        Rng rng(0x6a09e667f3bcc908ull ^ static_cast<uint64_t>(leaves[i]));
        double out[kMaxEmitterComponents];
        for (int cell = 0; cell < side * side; ++cell) {
            const double u = ((cell % side) + rng.uniform()) / side;
            const double v = ((cell / side) + rng.uniform()) / side;
            const ReceiverPoint p{pointOnElement(e, u, v), e.normal, e.polygon};
            for (size_t j = 0; j < J;) {
                const Light& l = scene_.lights[static_cast<size_t>(emitterLights_[j])];
                Rng own(rng.next());
                l.emitter->unitIrradiance(*vis_, p, options_.directRays, own, out);
                const size_t n = std::min(static_cast<size_t>(l.emitter->components()), J - j);
                for (size_t c = 0; c < n; ++c) H[j + c] += out[c];
                j += std::max<size_t>(n, 1);
            }
        }
        for (size_t j = 0; j < J; ++j) H[j] /= side * side;
    });
    sumDirectIrradiance();
}

void HierarchicalSolver::sumDirectIrradiance() {
    const size_t J = emitterLights_.size();
    directPower_ = Rgb{};
    if (J == 0) {
        // No emitter, or none left: no leaf keeps a removed one's light (a viewer session
        // that added a point lamp, then the next session, would see it in B before it adds
        // its own).
        for (Node& e : h_.nodes) e.Hx = Rgb{};
        return;
    }
    Hunit_.resize(h_.nodes.size() * J, 0.0);
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        e.Hx = Rgb{};
        for (size_t j = 0; j < J; ++j)
            e.Hx +=
                scene_.lights[static_cast<size_t>(emitterLights_[j])].radiance * Hunit_[n * J + j];
        directPower_ += e.Hx * e.area;
    }
}

void HierarchicalSolver::refreshEmitterLight(DynamicUpdate& report) {
    if (emitterLights_.empty()) return;
    const size_t J = emitterLights_.size();
    const size_t before = Hunit_.size() / J;
    const std::vector<double> old = Hunit_;
    updateDirectIrradiance(/*all=*/true);
    for (size_t n = 0; n < before && n < h_.nodes.size(); ++n) {
        const Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        for (size_t j = 0; j < J; ++j)
            if (old[n * J + j] != Hunit_[n * J + j]) {
                report.shadowLeaves.push_back(static_cast<int>(n));
                break;
            }
    }
    std::sort(report.shadowLeaves.begin(), report.shadowLeaves.end());
    report.shadowLeaves.erase(std::unique(report.shadowLeaves.begin(), report.shadowLeaves.end()),
                              report.shadowLeaves.end());
}

double HierarchicalSolver::sourcePower() const {
    return (scene_.emittedPower() + directPower_).maxComponent();
}

}  // namespace radiosity
