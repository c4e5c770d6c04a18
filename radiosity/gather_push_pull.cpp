// One sweep of the solution (HSA91): every receiver gathers F V B over its links, then
// push-pull hands what each node gathered down to the leaves and pulls the radiosities up.
//
// The push-pull reads a compact layout of the hierarchy (PushPullLayout, solver.h), rebuilt
// when the links or the nodes change: each node's parent, and for the clusters that
// receive links their frames. A polygon's root element then finds what its cluster
// ancestors gathered by walking the parents in that array, rather than the nodes (750
// bytes each, one directional irradiance of 144 bytes read per ancestor to find it empty):
// that walk was a fifth of a jittered 215 k-triangle room's solve. The sums are the same,
// in the same order, so the radiosities are bit-identical to the walk over the nodes.
#include "radiosity/parallel.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "radiosity/tree_walks.h"

namespace radiosity {

void HierarchicalSolver::gatherInto(const Link& l) {
    Node& R = h_.nodes[l.receiver];
    const Node& S = h_.nodes[l.source];
    const Rgb H = S.Bsent * (l.F * static_cast<double>(l.V));
    if (R.isCluster())
        h_.Hv(R).add(H, h_.toFrame(R, linkDirection(R, S)));
    else if (reflects(S))
        R.H += H;
    else
        R.Hd += H;
}

void HierarchicalSolver::gatherRun(size_t i) {
    Node& R = h_.nodes[links_.receiver(i)];
    const int first = links_.start(i), last = links_.start(i + 1);
    if (R.isCluster()) {
        const Vec3* dir = layout_.dir.data() + layout_.dirStart[i] - first;
        DirectionalIrradiance& Hv = h_.Hv(R);
        for (int k = first; k < last; ++k) {
            const Link& l = links_[k];
            Hv.add(h_.nodes[l.source].Bsent * (l.F * static_cast<double>(l.V)), dir[k]);
        }
        return;
    }
    for (int k = first; k < last; ++k) {
        const Link& l = links_[k];
        const Node& S = h_.nodes[l.source];
        const Rgb H = S.Bsent * (l.F * static_cast<double>(l.V));
        if (reflects(S))
            R.H += H;
        else
            R.Hd += H;
    }
}

void HierarchicalSolver::buildPushPullLayout() {
    const auto& nodes = h_.nodes;
    PushPullLayout& L = layout_;
    L.parent.resize(nodes.size());
    L.slot.assign(nodes.size(), -1);
    L.frame.clear();
    for (size_t n = 0; n < nodes.size(); ++n) L.parent[n] = nodes[n].parent;
    const size_t runs = links_.receiverCount();  // indexes the links if they changed
    L.dirStart.assign(runs, -1);
    L.dir.clear();
    for (size_t i = 0; i < runs; ++i) {
        const int r = links_.receiver(i);
        if (!nodes[r].isCluster()) continue;
        L.slot[r] = static_cast<int>(L.frame.size());
        L.frame.push_back(h_.frame(nodes[r]));
        // The direction of each link's source in the receiving cluster's frame, which the
        // gather bins by (it was a tenth of the gather's time, recomputed every sweep).
        L.dirStart[i] = static_cast<int>(L.dir.size());
        for (int k = links_.start(i); k < links_.start(i + 1); ++k)
            L.dir.push_back(h_.toFrame(nodes[r], linkDirection(nodes[r], nodes[links_[k].source])));
    }
    h_.clustersAndRoots(L.clusters, L.roots);
    L.nodes = nodes.size();
    L.generation = links_.generation();
    L.valid = true;
}

bool HierarchicalSolver::layoutCurrent() const {
    return layout_.valid && layout_.nodes == h_.nodes.size() &&
           layout_.generation == links_.generation();
}

Rgb HierarchicalSolver::fromClusterAncestors(int element) const {
    // What the cluster ancestors of a polygon's root element gathered, each taken by the
    // element's normal in that cluster's frame (directional_irradiance.h). Only clusters
    // that receive links gather anything.
    const Node& e = h_.nodes[element];
    Rgb H;
    if (layoutCurrent()) {
        for (int a = layout_.parent[element]; a >= 0; a = layout_.parent[a]) {
            const int s = layout_.slot[a];
            if (s < 0) continue;
            const DirectionalIrradiance& d = h_.Hv(h_.nodes[a]);
            if (d.isZero()) continue;
            H += d.onto(toFrame(layout_.frame[s], e.normal));
        }
        return H;
    }
    // No layout (an object being linked): the walk over the nodes.
    return fromClusters(h_, element,
                        [&](int a) -> const DirectionalIrradiance& { return h_.Hv(h_.nodes[a]); });
}

double HierarchicalSolver::sweep() {
    links_.index();
    if (!layoutCurrent()) buildPushPullLayout();
    auto t0 = Clock::now();
    // Only receivers gather; the rest keep zero from the last full clear (after the links
    // changed, a node that stopped receiving still holds its last sum).
    const auto clear = [&](Node& n) {
        n.H = n.Hd = Rgb{};
        if (n.isCluster()) h_.Hv(n) = DirectionalIrradiance{};
    };
    if (sweptGeneration_ != links_.generation()) {
        parallelFor(h_.nodes.size(), 4096, [&](size_t i) { clear(h_.nodes[i]); });
        sweptGeneration_ = links_.generation();
    } else {
        parallelFor(links_.receiverCount(), 1024,
                    [&](size_t i) { clear(h_.nodes[links_.receiver(i)]); });
    }
    // Gather (HSA91): each receiver sums F V B over its links, in a fixed order, so the
    // result does not depend on the thread count.
    parallelFor(links_.receiverCount(), 64, [&](size_t i) { gatherRun(i); });
    timing_.timeGather += secondsSince(t0);
    t0 = Clock::now();
    pushPullAll();
    timing_.timePushPull += secondsSince(t0);
    ++timing_.sweeps;
    const Node& root = h_.nodes[Hierarchy::kRoot];
    return root.B.maxComponent() * root.area;
}

void HierarchicalSolver::pushPull(int node, const Rgb& Hdown, const Rgb& HdDown) {
    Node& n = h_.nodes[node];
    Rgb H, Hd;
    if (!n.isCluster()) {
        // An element: what its ancestor elements gathered and its own links; a polygon's
        // root element also what the clusters above it gathered, by its orientation.
        const bool root = n.parent < 0 || h_.nodes[n.parent].isCluster();
        H = Hdown + n.H + (root ? fromClusterAncestors(node) : Rgb{});
        Hd = HdDown + n.Hd;
        if (n.isLeaf()) {
            n.B = n.E + n.rho * (Hd + n.Hx + H * n.gatherScale);
            n.Bsent = n.B * n.sendScale;
            return;
        }
    }
    // Push down, pull B up as the area-weighted mean.
    Rgb B, Bsent;
    double area = 0;
    const int first = n.firstChild, count = n.childCount;
    for (int k = 0; k < count; ++k) {
        pushPull(first + k, H, Hd);
        const Node& c = h_.nodes[first + k];
        B += c.B * c.area;
        Bsent += c.Bsent * c.area;
        area += c.area;
    }
    Node& m = h_.nodes[node];
    m.B = area > 0 ? B * (1.0 / area) : Rgb{};  // guard: no area below
    m.Bsent = area > 0 ? Bsent * (1.0 / area) : Rgb{};
}

void HierarchicalSolver::pushPullAll() {
    // The polygons' element trees are independent once their cluster ancestors have
    // gathered: each is pushed down and pulled up on its own, in parallel; then the
    // clusters take their means bottom-up. The sums are those of pushPull(root) in the
    // same order, so the result does not depend on the thread count.
    if (!layoutCurrent()) buildPushPullLayout();
    const std::vector<int>&clusters = layout_.clusters, &roots = layout_.roots;
    parallelFor(roots.size(), 256, [&](size_t i) { pushPull(roots[i], Rgb{}, Rgb{}); });
    for (auto it = clusters.rbegin(); it != clusters.rend(); ++it) {
        Node& n = h_.nodes[*it];
        Rgb B, Bsent;
        double area = 0;
        for (int k = 0; k < n.childCount; ++k) {
            const Node& c = h_.nodes[n.firstChild + k];
            B += c.B * c.area;
            Bsent += c.Bsent * c.area;
            area += c.area;
        }
        n.B = area > 0 ? B * (1.0 / area) : Rgb{};  // guard: no area below
        n.Bsent = area > 0 ? Bsent * (1.0 / area) : Rgb{};
    }
}

}  // namespace radiosity
