// Importance from the photo's camera (Smits, Arvo & Salesin 1992, "An importance-driven
// radiosity algorithm"): the adjoint of the radiosity equation, emitted by what the view
// shows, says how much each surface's light matters to the picture. Smits et al. solve it
// with its own hierarchy of links and weigh the refinement's error by it; here the
// camera is fixed and its item buffer says which polygons it sees (the direct importance,
// 1 or 0), and one bounce through the radiosity links themselves (read transposed) adds
// the surfaces that light what is seen: I(s) = I_seen(s) + the mean over where s's light
// goes (weighted by the power each link carries) of rho_r I_seen(r). A second bounce would add at
// most rho^2 of the first; the floor (HierarchicalSolver::kImportanceFloor) keeps every surface
// refined at least at a tenth of the plain criterion for what the bounces miss.
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "radiosity/solver.h"

namespace radiosity {

namespace {

// A value per polygon, or none.
void checkPerPolygon(const char* what, const std::vector<double>& values, size_t polygons) {
    if (!values.empty() && values.size() != polygons)
        throw std::invalid_argument(std::string(what) + ": " + std::to_string(values.size()) +
                                    " values for " + std::to_string(polygons) + " polygons");
}

}  // namespace

void HierarchicalSolver::setCameraImportance(std::vector<double> seen) {
    checkPerPolygon("setCameraImportance", seen, scene_.polygons.size());
    seenImportance_ = std::move(seen);
    importanceBounced_ = false;
    polygonImportance_.clear();
    clusterImportance_.clear();
    if (!seenImportance_.empty()) updateImportance(/*bounce=*/false);
}

void HierarchicalSolver::setCameraSeen(std::vector<double> seen) {
    checkPerPolygon("setCameraSeen", seen, scene_.polygons.size());
    cameraSeen_ = std::move(seen);
}

double HierarchicalSolver::seenPowerShare() const {
    if (cameraSeen_.empty() || !(options_.seenPowerFloor < 1)) return 1.0;
    // The emitters' direct light on the leaves (updateDirectIrradiance), by channel: a
    // sky's coefficient may light with either sign, the sum over its components does not.
    Rgb seen, all;
    for (const Node& e : h_.nodes) {
        if (e.isCluster() || !e.isLeaf() || e.polygon < 0) continue;
        const Rgb p = e.Hx * e.area;
        all += p;
        const auto i = static_cast<size_t>(e.polygon);
        if (i >= cameraSeen_.size() || cameraSeen_[i] > 0) seen += p;  // an inserted polygon: seen
    }
    const Rgb lamps = scene_.emittedPower();
    const double denominator = (all + lamps).maxComponent();
    if (!(denominator > 0)) return 1.0;  // no light: nothing to refine for
    return std::clamp((seen + lamps).maxComponent() / denominator, options_.seenPowerFloor, 1.0);
}

void HierarchicalSolver::setPowerThreshold() {
    const double share = seenPowerShare();
    powerThreshold_ = options_.epsilon * sourcePower() * share;
    if (share < 1) {
        char msg[160];
        std::snprintf(msg, sizeof msg,
                      "  refinement threshold: epsilon times %.1f %% of the emitted power (what "
                      "reaches the surfaces the camera sees)",
                      100 * share);
        report(msg);
    }
}

double HierarchicalSolver::importanceOf(int node) const {
    if (polygonImportance_.empty()) return 1.0;
    const Node& n = h_.nodes[static_cast<size_t>(node)];
    if (!n.isCluster())
        return n.polygon >= 0 && static_cast<size_t>(n.polygon) < polygonImportance_.size()
                   ? polygonImportance_[static_cast<size_t>(n.polygon)]
                   : 1.0;
    // A cluster made after the importance (an inserted object) counts fully.
    return static_cast<size_t>(node) < clusterImportance_.size()
               ? static_cast<double>(clusterImportance_[static_cast<size_t>(node)])
               : 1.0;
}

void HierarchicalSolver::updateImportance(bool bounce) {
    const auto& nodes = h_.nodes;
    const size_t nn = nodes.size(), np = scene_.polygons.size();
    // Nodes in depth-first pre-order: parents before children, and reversed, children
    // before parents.
    std::vector<int> order;
    order.reserve(nn);
    std::vector<int> stack{Hierarchy::kRoot};
    while (!stack.empty()) {
        const int n = stack.back();
        stack.pop_back();
        order.push_back(n);
        for (int k = 0; k < nodes[n].childCount; ++k) stack.push_back(nodes[n].firstChild + k);
    }
    // The seen share of each node's area (area-weighted direct importance), bottom-up.
    std::vector<double> seenArea(nn, 0.0);
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        const Node& n = nodes[*it];
        if (n.isLeaf() && !n.isCluster())
            seenArea[*it] = seenImportance_[static_cast<size_t>(n.polygon)] * n.area;
        if (n.parent >= 0) seenArea[n.parent] += seenArea[*it];
    }
    std::vector<double> bounced(np, 0.0);
    if (bounce) {
        // The adjoint's first bounce at each source s: where its light goes, weighted by
        // what each link carries, F_rs V A_r (the power s sends to r, per unit B_s), the
        // mean of rho_r times the seen share of r. A ratio over the links of s, so that the
        // cluster kernels' normalisation (a disc of the projected area) cancels.
        std::vector<double> num(nn, 0.0), den(nn, 0.0);
        for (const Link& l : links_.byReceiver()) {
            const Node& R = nodes[l.receiver];
            if (!(R.area > 0)) continue;
            const double w = l.F * static_cast<double>(l.V) * R.area;
            num[l.source] += w * R.rho.maxComponent() * seenArea[l.receiver] / R.area;
            den[l.source] += w;
        }
        // A polygon sends through its own elements' links and its clusters': the sums down
        // the tree, the largest ratio over the polygon's elements.
        for (const int n : order) {
            if (nodes[n].parent >= 0) {
                num[n] += num[nodes[n].parent];
                den[n] += den[nodes[n].parent];
            }
            if (!nodes[n].isCluster() && den[n] > 0) {
                double& b = bounced[static_cast<size_t>(nodes[n].polygon)];
                b = std::max(b, num[n] / den[n]);
            }
        }
    }
    polygonImportance_.assign(np, 1.0);
    for (size_t p = 0; p < np; ++p)
        polygonImportance_[p] = std::clamp(seenImportance_[p] + bounced[p], kImportanceFloor, 1.0);
    // A cluster: the largest importance of its polygons, bottom-up.
    clusterImportance_.assign(nn, 0.0f);
    for (auto it = order.rbegin(); it != order.rend(); ++it) {
        const Node& n = nodes[*it];
        float& mine = clusterImportance_[static_cast<size_t>(*it)];
        if (!n.isCluster())
            mine = static_cast<float>(polygonImportance_[static_cast<size_t>(n.polygon)]);
        if (n.parent >= 0) {
            float& up = clusterImportance_[static_cast<size_t>(n.parent)];
            up = std::max(up, mine);
        }
    }
}

}  // namespace radiosity
