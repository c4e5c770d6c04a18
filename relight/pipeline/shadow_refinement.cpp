#include "relight/pipeline/shadow_refinement.h"

#include <algorithm>
#include <cmath>
#include <deque>

namespace relight {

using radiosity::Rgb;
using Exchange = std::vector<radiosity::HierarchicalSolver::LightExchange>;

namespace {

struct Comparer {
    const ShadowRefinementOptions& o;
    std::vector<double> emittance;  // per light: max channel of pi L (only relative values)

    bool similarColour(const Rgb& a, const Rgb& b) const {
        const double scale = std::max(a.maxComponent(), b.maxComponent());
        if (!(scale > 0)) return true;  // both black
        double d = 0;
        for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(a[c] - b[c]));
        return d < o.colourThreshold * scale;
    }

    bool similarVisibility(const Exchange& a, const Exchange& b) const {
        double total = 0;
        for (size_t s = 0; s < a.size(); ++s) total += (a[s].F + b[s].F) * emittance[s];
        if (!(total > 0)) return true;  // no direct light on either: nothing to compare
        for (size_t s = 0; s < a.size(); ++s) {
            if ((a[s].F + b[s].F) * emittance[s] < o.minShare * total) continue;
            // Guard: a leaf that does not face the light (F = 0) gets none of it: V = 0.
            const double va = a[s].F > 0 ? a[s].FV / a[s].F : 0.0;
            const double vb = b[s].F > 0 ? b[s].FV / b[s].F : 0.0;
            if (std::abs(va - vb) >= o.visibilityThreshold) return false;
        }
        return true;
    }
};

}  // namespace

ShadowRefinementReport refineShadowBoundaries(radiosity::HierarchicalSolver& solver,
                                              LeafTexture& texture,
                                              const ShadowRefinementOptions& o) {
    ShadowRefinementReport rep;
    const radiosity::Hierarchy& h = solver.hierarchy();
    const radiosity::Scene& scene = solver.scene();
    Comparer cmp{o, {}};
    for (const auto& light : scene.lights) cmp.emittance.push_back(light.radiance.maxComponent());

    // Light exchange per node: read from the links before the first split (the receiver
    // index is valid), then kept up to date from what each split reports.
    std::vector<Exchange> exchange(h.nodes.size());
    std::deque<int> work;
    for (int n = 0; n < static_cast<int>(h.nodes.size()); ++n) {
        const radiosity::Node& node = h.nodes[n];
        if (node.isCluster() || !node.isLeaf() || scene.polygons[node.polygon].light >= 0) continue;
        exchange[n] = solver.lightExchange(n);
        ++rep.leavesBefore;
        if (texture.samples(n) >= o.minSamples) work.push_back(n);
    }
    auto hasColour = [&](int n) { return texture.samples(n) >= o.minSamples; };
    std::vector<std::vector<radiosity::HierarchicalSolver::LightExchange>> children;
    int splits = 0;
    while (!work.empty() && splits < o.maxSplits) {
        if (radiosity::Clock::now() >= o.until) {
            rep.budgetReached = true;
            rep.waiting = static_cast<int>(work.size());
            break;
        }
        const int i = work.front();
        work.pop_front();
        if (!h.nodes[i].isLeaf() || !hasColour(i)) continue;
        ++rep.examined;
        const Rgb ci = texture.colour(i);
        int why = 0;  // 1: same colour, other visibility; 2: other colour, same visibility
        for (int n : h.edgeNeighbours(i)) {
            if (!hasColour(n) || exchange[n].empty()) continue;
            const bool colour = cmp.similarColour(ci, texture.colour(n));
            const bool vis = cmp.similarVisibility(exchange[i], exchange[n]);
            if (colour && !vis)
                why = 1;
            else if (!colour && vis)
                why = 2;
            if (why) break;
        }
        if (!why || !solver.splitForLights(i, &children)) continue;
        ++splits;
        texture.split(i);
        const radiosity::Node& parent = h.nodes[i];
        bool changed = false;
        for (int k = 0; k < parent.childCount; ++k)
            changed = changed || !cmp.similarVisibility(children[k], exchange[i]);
        if (!changed) {  // the split showed no visibility change: merge back (Fig. 12)
            texture.merge(i);
            solver.unsplit(i);
            ++rep.undone;
            continue;
        }
        (why == 1 ? rep.splitSameColour : rep.splitDifferentColour)++;
        exchange.resize(h.nodes.size());
        for (int k = 0; k < parent.childCount; ++k) {
            exchange[parent.firstChild + k] = children[k];
            work.push_back(parent.firstChild + k);
        }
        if (o.progress && splits % 500 == 0)
            o.progress("shadow refinement: " + std::to_string(splits) + " splits");
    }
    solver.gatherPushPull();
    rep.leavesAfter = rep.leavesBefore + 3 * (rep.splitSameColour + rep.splitDifferentColour);
    return rep;
}

}  // namespace relight
