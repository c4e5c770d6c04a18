// Walks of the hierarchy shared by the solver's passes (solver.cpp, energy_bound.cpp,
// send_balance.cpp, gather_push_pull.cpp): the order in which a pass visits the nodes,
// sums or area means pulled up from the leaves, and what a polygon's root element takes
// from the directional irradiance of its cluster ancestors.
#pragma once

#include <vector>

#include "radiosity/hierarchy.h"

namespace radiosity {

/// Every node reachable from the root, each after its parent (parents do not always
/// precede their children in the node array: an attached object's cluster).
inline std::vector<int> preOrder(const Hierarchy& h) {
    std::vector<int> pre;
    pre.reserve(h.nodes.size());
    for (std::vector<int> stack{Hierarchy::kRoot}; !stack.empty();) {
        const int n = stack.back();
        stack.pop_back();
        pre.push_back(n);
        for (int k = 0; k < h.nodes[n].childCount; ++k) stack.push_back(h.nodes[n].firstChild + k);
    }
    return pre;
}

/// Pulls x up the tree, children first: on entry x holds the leaves' values (0 elsewhere)
/// and xa their areas (0 elsewhere); on return x holds at every node the sum of its
/// leaves' values, or with `mean` (the leaves' values then given times their areas) their
/// area-weighted mean, and xa the area of its leaves.
inline void pullUp(const std::vector<int>& pre, const std::vector<int>& parent,
                   std::vector<double>& x, std::vector<double>& xa, bool mean) {
    for (auto it = pre.rbegin(); it != pre.rend(); ++it)
        if (parent[*it] >= 0) {
            x[parent[*it]] += x[*it];
            xa[parent[*it]] += xa[*it];
        }
    if (mean)
        for (size_t n = 0; n < x.size(); ++n) x[n] = xa[n] > 0 ? x[n] / xa[n] : 0.0;  // guard
}

/// What the cluster ancestors of a polygon's root element gathered (ownHv(a): cluster a's
/// directional irradiance), each taken by the element's normal in that cluster's frame.
template <class OwnHv>
Rgb fromClusters(const Hierarchy& h, int element, const OwnHv& ownHv) {
    const Node& e = h.nodes[element];
    Rgb H;
    for (int a = e.parent; a >= 0; a = h.nodes[a].parent) {
        const DirectionalIrradiance& d = ownHv(a);
        if (!d.isZero()) H += d.onto(h.toFrame(h.nodes[a], e.normal));
    }
    return H;
}

}  // namespace radiosity
