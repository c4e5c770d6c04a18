#include "radiosity/light_response.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "radiosity/detail/transfer.h"
#include "radiosity/directional_irradiance.h"
#include "radiosity/parallel.h"

namespace radiosity {

namespace {

/// See the convergence test in LightResponses().
constexpr double kPowerFloor = 1e-3;

/// What stays fixed over the sweeps: the receivers' runs of links, the clusters in
/// top-down order, the polygons' root elements, and for each root the cluster ancestors
/// that gather light with the root's normal in their frames (fromClusters in solver.cpp).
struct SweepLayout {
    std::vector<int> runStart;     ///< links of run i: [runStart[i], runStart[i + 1])
    std::vector<int> clusterSlot;  ///< node -> its slot among the gathering clusters, or -1
    int slots = 0;
    std::vector<int> clustersTopDown;  ///< every cluster after its parent
    std::vector<int> roots;            ///< polygon root elements
    std::vector<int> ancestorStart;    ///< per root: [start[i], start[i + 1]) in the two below
    std::vector<int> ancestorSlot;
    std::vector<Vec3> ancestorNormal;  ///< the root's normal in that ancestor's frame
    /// Per run of a cluster receiver: its links' source directions in its frame,
    /// dir[dirStart[run] + k] for its k-th link (-1 for an element receiver).
    std::vector<int> dirStart;
    std::vector<Vec3> dir;

    SweepLayout(const Hierarchy& h, const std::vector<Link>& links) {
        const auto& nodes = h.nodes;
        clusterSlot.assign(nodes.size(), -1);
        std::vector<char> started(nodes.size(), 0);
        for (size_t k = 0; k < links.size(); ++k) {
            if (k == 0 || links[k].receiver != links[k - 1].receiver) {
                // One run per receiver, or two threads would add to its irradiance at once.
                if (started[links[k].receiver]++)
                    throw std::logic_error("LightResponses: links not grouped by receiver");
                runStart.push_back(static_cast<int>(k));
            }
            const int r = links[k].receiver;
            if (nodes[r].isCluster() && clusterSlot[r] < 0) clusterSlot[r] = slots++;
        }
        runStart.push_back(static_cast<int>(links.size()));
        dirStart.assign(runStart.size() - 1, -1);
        for (size_t run = 0; run + 1 < runStart.size(); ++run) {
            const Node& R = nodes[links[runStart[run]].receiver];
            if (!R.isCluster()) continue;
            dirStart[run] = static_cast<int>(dir.size());
            for (int k = runStart[run]; k < runStart[run + 1]; ++k)
                dir.push_back(h.toFrame(R, linkDirection(R, nodes[links[k].source])));
        }
        h.clustersAndRoots(clustersTopDown, roots);
        ancestorStart.reserve(roots.size() + 1);
        for (int root : roots) {
            ancestorStart.push_back(static_cast<int>(ancestorSlot.size()));
            const Vec3& normal = nodes[root].normal;
            for (int a = nodes[root].parent; a >= 0; a = nodes[a].parent)
                if (clusterSlot[a] >= 0) {
                    ancestorSlot.push_back(clusterSlot[a]);
                    ancestorNormal.push_back(h.toFrame(nodes[a], normal));
                }
        }
        ancestorStart.push_back(static_cast<int>(ancestorSlot.size()));
    }
};

/// Per-light values of every node, [node * K + l].
class PerLight {
  public:
    PerLight(size_t nodes, int K) : K_(K), v_(nodes * static_cast<size_t>(K)) {}
    /// Over `values` (nodes x K of them), taken as they are.
    PerLight(std::vector<Rgb> values, int K) : K_(K), v_(std::move(values)) {}
    Rgb* operator[](size_t node) { return v_.data() + node * K_; }
    const Rgb* operator[](size_t node) const { return v_.data() + node * K_; }
    void clear() { std::fill(v_.begin(), v_.end(), Rgb{}); }
    std::vector<Rgb>& values() { return v_; }

  private:
    size_t K_;
    std::vector<Rgb> v_;
};

/// E_l, light l's emittance at radiance 1, at the leaves: a leaf of light l's faces has
/// unit[l] for light l and nothing for the others. Found from the leaf's polygon rather than
/// held as nodes x lights values (a fifth of the responses' arrays: 182 MB of the peak of
/// the stair hall cut into 1.57 M faces, bench/RESULTS.md).
class UnitEmittance {
  public:
    UnitEmittance(const Hierarchy& h, const Scene& scene) : light_(h.nodes.size(), -1) {
        for (const Light& light : scene.lights) {
            Light one = light;
            one.radiance = Rgb::gray(1.0);
            unit_.push_back(one.emittance());
        }
        // One index a node, read by every sweep's push to the leaves: not the polygon's
        // record, a cache line a leaf.
        for (size_t n = 0; n < h.nodes.size(); ++n) {
            const Node& e = h.nodes[n];
            if (!e.isCluster() && e.isLeaf()) light_[n] = scene.polygons[e.polygon].light;
        }
    }
    /// The light whose face leaf element `node` is, or -1.
    int lightOf(size_t node) const { return light_[node]; }
    /// Light l's unit emittance, what a leaf of its faces emits at radiance 1.
    const Rgb& unit(int l) const { return unit_[static_cast<size_t>(l)]; }
    Rgb at(size_t node, int l) const { return lightOf(node) == l ? unit(l) : Rgb{}; }

  private:
    std::vector<int> light_;
    std::vector<Rgb> unit_;
};

/// The sweeps: the same gather and push-pull as HierarchicalSolver::sweep(), with K values
/// per node (one per light) and on arrays of their own rather than the nodes.
class ResponseSweeps {
  public:
    ResponseSweeps(const Hierarchy& h, const std::vector<Link>& links, int K,
                   const UnitEmittance& E, PerLight& B, const PerLight* X = nullptr)
        : h_(h),
          X_(X),
          links_(links),
          layout_(h, links),
          K_(K),
          E_(E),
          B_(B),
          S_(h.nodes.size(), K),
          H_(h.nodes.size(), K),
          Hd_(h.nodes.size(), K),
          Hv_(static_cast<size_t>(layout_.slots) * K) {}

    /// What each node sends from B (leaves: B sendScale; the rest: area means). Called
    /// once B is set, before the first sweep.
    void setSent() {
        const auto& nodes = h_.nodes;
        for (size_t n = 0; n < nodes.size(); ++n) {
            const Node& e = nodes[n];
            if (e.isCluster() || !e.isLeaf()) continue;
            for (int l = 0; l < K_; ++l) S_[n][l] = B_[n][l] * e.sendScale;
        }
        pullAll(S_);
    }

    /// One gather over all links, then push-pull. Fills `power` with each light's total
    /// reflected-plus-emitted power (max channel times area at the root).
    void sweep(std::vector<double>& power) {
        H_.clear();
        Hd_.clear();
        std::fill(Hv_.begin(), Hv_.end(), DirectionalIrradiance{});
        gather();
        pushToLeaves();
        pullClusters();
        const Node& root = h_.nodes[Hierarchy::kRoot];
        for (int l = 0; l < K_; ++l) power[l] = B_[Hierarchy::kRoot][l].maxComponent() * root.area;
    }

    /// Cluster means of E (the leaves' values set).
    void pullClusters(PerLight& x) const {
        for (auto it = layout_.clustersTopDown.rbegin(); it != layout_.clustersTopDown.rend(); ++it)
            pullMean(*it, x);
    }
    /// Element means below polygon roots, then clusters.
    void pullAll(PerLight& x) const {
        parallelFor(layout_.roots.size(), 256,
                    [&](size_t i) { pullElements(layout_.roots[i], x); });
        pullClusters(x);
    }

  private:
    void gather() {
        const auto& nodes = h_.nodes;
        const size_t runs = layout_.runStart.size() - 1;
        parallelFor(runs, 64, [&](size_t i) { gatherRun(nodes, i); });
    }

    void gatherRun(const std::vector<Node>& nodes, size_t run) {
        const int first = layout_.runStart[run], last = layout_.runStart[run + 1];
        const int r = links_[first].receiver;
        const int slot = layout_.clusterSlot[r];
        for (int k = first; k < last; ++k) {
            const Link& link = links_[k];
            const double FV = link.F * static_cast<double>(link.V);
            const Rgb* Bs = S_[link.source];  // what the source sends
            if (slot >= 0) {
                const Vec3& w = layout_.dir[layout_.dirStart[run] + (k - first)];
                DirectionalIrradiance* Hv = Hv_.data() + static_cast<size_t>(slot) * K_;
                for (int l = 0; l < K_; ++l) Hv[l].add(Bs[l] * FV, w);
            } else {
                Rgb* H = reflects(nodes[link.source]) ? H_[r] : Hd_[r];
                for (int l = 0; l < K_; ++l) H[l] += Bs[l] * FV;
            }
        }
    }

    /// Each polygon's element tree: what its cluster ancestors gathered, by its normal,
    /// handed down with its elements' own; leaves take B = E + rho (Hd + H gatherScale).
    void pushToLeaves() {
        parallelForChunks(layout_.roots.size(), 256, [&](size_t begin, size_t end) {
            std::vector<Rgb> down(2 * static_cast<size_t>(K_));
            for (size_t i = begin; i != end; ++i) {
                std::fill(down.begin(), down.end(), Rgb{});
                for (int a = layout_.ancestorStart[i]; a < layout_.ancestorStart[i + 1]; ++a) {
                    const DirectionalIrradiance* Hv =
                        Hv_.data() + static_cast<size_t>(layout_.ancestorSlot[a]) * K_;
                    const Vec3& n = layout_.ancestorNormal[a];
                    for (int l = 0; l < K_; ++l) down[l] += Hv[l].onto(n);
                }
                pushElement(layout_.roots[i], down.data(), down.data() + K_);
            }
        });
    }

    void pushElement(int node, const Rgb* Hdown, const Rgb* HdDown) {
        const Node& n = h_.nodes[node];
        const Rgb *H = H_[node], *Hd = Hd_[node];
        if (n.isLeaf()) {
            Rgb* B = B_[node];
            Rgb* S = S_[node];
            for (int l = 0; l < K_; ++l) {
                B[l] = n.rho * (HdDown[l] + Hd[l] + (Hdown[l] + H[l]) * n.gatherScale);
                S[l] = B[l] * n.sendScale;
            }
            const int emits = E_.lightOf(static_cast<size_t>(node));
            if (emits >= 0) {
                B[emits] += E_.unit(emits);
                S[emits] = B[emits] * n.sendScale;
            }
            if (X_) {  // the emitters' direct light reflected (HierarchicalSolver::Node::Hx)
                const Rgb* X = (*X_)[node];
                for (int l = 0; l < K_; ++l) {
                    B[l] += X[l];
                    S[l] = B[l] * n.sendScale;
                }
            }
            return;
        }
        std::vector<Rgb> down(2 * static_cast<size_t>(K_));
        for (int l = 0; l < K_; ++l) {
            down[l] = Hdown[l] + H[l];
            down[K_ + l] = HdDown[l] + Hd[l];
        }
        for (int k = 0; k < n.childCount; ++k)
            pushElement(n.firstChild + k, down.data(), down.data() + K_);
        pullMean(node, B_);
        pullMean(node, S_);
    }

    void pullElements(int node, PerLight& x) const {
        const Node& n = h_.nodes[node];
        if (n.isLeaf()) return;
        for (int k = 0; k < n.childCount; ++k) pullElements(n.firstChild + k, x);
        pullMean(node, x);
    }

    void pullClusters() {
        pullClusters(B_);
        pullClusters(S_);
    }

    /// x(node) = area-weighted mean of its children's (guarded: no area below gives 0).
    void pullMean(int node, PerLight& x) const {
        const Node& n = h_.nodes[node];
        Rgb* out = x[node];
        std::fill(out, out + K_, Rgb{});
        double area = 0;
        for (int k = 0; k < n.childCount; ++k) {
            const int c = n.firstChild + k;
            const double a = h_.nodes[c].area;
            const Rgb* xc = x[c];
            for (int l = 0; l < K_; ++l) out[l] += xc[l] * a;
            area += a;
        }
        const double inv = area > 0 ? 1.0 / area : 0.0;
        for (int l = 0; l < K_; ++l) out[l] = out[l] * inv;
    }

    const Hierarchy& h_;
    const PerLight* X_;  ///< rho H_l of the emitter lights at the leaves, or null
    const std::vector<Link>& links_;
    SweepLayout layout_;
    int K_;
    const UnitEmittance& E_;
    PerLight& B_;
    PerLight S_;  ///< what each node sends through its links (HierarchicalSolver::Node::Bsent)
    PerLight H_, Hd_;
    std::vector<DirectionalIrradiance> Hv_;
};

}  // namespace

LightResponses::LightResponses(HierarchicalSolver& solver, std::unique_ptr<LightResponses> warm)
    : lights_(static_cast<int>(solver.scene().lights.size())) {
    solver.ensureLightLinks();
    const Hierarchy& h = solver.hierarchy();
    const Scene& scene = solver.scene();
    const auto& nodes = h.nodes;
    const size_t N = nodes.size();
    if (lights_ == 0) return;

    // E_l: light l's faces at radiance 1, nothing elsewhere.
    const UnitEmittance E(h, scene);
    // B in the warm start's storage, when it fits, where its responses are added below.
    const bool warmFits =
        warm && warm->lights_ == lights_ && warm->R_.size() == N * static_cast<size_t>(lights_);
    PerLight B = warmFits ? PerLight(std::move(warm->R_), lights_) : PerLight(N, lights_);
    warm.reset();
    // Lights that are not faces (radiosity/emitter.h): their direct light, reflected, is
    // each leaf's source X_l = rho H_l (H_l per unit strength, the solver's Hx split).
    std::unique_ptr<PerLight> X;
    if (!solver.emitterLights().empty()) {
        X = std::make_unique<PerLight>(N, lights_);
        const std::vector<int>& lights = solver.emitterLights();
        for (size_t n = 0; n < N; ++n) {
            const Node& e = nodes[n];
            if (e.isCluster() || !e.isLeaf()) continue;
            const std::span<const double> H = solver.directUnit(static_cast<int>(n));
            for (size_t j = 0; j < H.size(); ++j) (*X)[n][lights[j]] = e.rho * H[j];
        }
    }
    ResponseSweeps sweeps(h, solver.links(), lights_, E, B, X.get());
    // At the leaves, B = E + X + the warm responses, added in that order; the sweeps set the
    // other nodes' B from them (setSent reads the leaves only).
    for (size_t n = 0; n < N; ++n) {
        const Node& e = nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        for (int l = 0; l < lights_; ++l) {
            Rgb sum = E.at(n, l);
            if (X) sum += (*X)[n][l];
            if (warmFits) sum += B[n][l];
            B[n][l] = sum;
        }
    }
    sweeps.setSent();

    // Converged as HierarchicalSolver::gatherPushPull: for each light, the last change of
    // its total power and the geometric estimate of what is left both below the tolerance.
    const double tolerance = solver.options().tolerance;
    std::vector<double> power(lights_), previous(lights_, -1), previousDelta(lights_, -1);
    while (true) {
        sweeps.sweep(power);
        ++sweeps_;
        bool converged = true;
        // A sky's coefficient lights a scene with both signs (Y_k is negative over half
        // the sphere), so its total may be near zero: its change is measured against a
        // floor of kPowerFloor of the largest light's total too (lights with an emitter
        // only: faces keep their own total, as before).
        double largest = 0;
        for (int l = 0; l < lights_; ++l) largest = std::max(largest, std::abs(power[l]));
        for (int l = 0; l < lights_; ++l) {
            const double ref = scene.lights[l].emitter
                                   ? std::max(std::abs(power[l]), kPowerFloor * largest)
                                   : power[l];
            if (!std::isfinite(power[l]))
                throw SolverError("light responses: the response to light '" +
                                  scene.lights[l].name + "' is not finite after " +
                                  std::to_string(sweeps_) + " sweeps");
            if (sweeps_ == 1) {  // (a sky's coefficient may light with a negative total)
                converged = false;
            } else {
                const double delta = std::abs(power[l] - previous[l]);
                double q = previousDelta[l] > 0 ? delta / previousDelta[l] : 0.5;
                q = std::min(q, 0.999);  // guard: a stalled change gives a huge bound
                const double remaining = delta * q / (1.0 - q);
                if (delta > tolerance * ref || remaining > tolerance * ref) converged = false;
                previousDelta[l] = delta;
            }
            previous[l] = power[l];
        }
        if (converged) break;
        if (sweeps_ >= solver.options().maxSweeps)
            throw SolverError("light responses did not converge after " + std::to_string(sweeps_) +
                              " gather/push-pull sweeps");
    }
    // R = B - E in B's storage, at the leaves; above them, the area means of the leaves' R,
    // as B's and E's are of theirs.
    for (size_t n = 0; n < N; ++n) {
        const int l = E.lightOf(n);
        if (l >= 0) B[n][l] = B[n][l] - E.unit(l);
    }
    sweeps.pullAll(B);
    R_ = std::move(B.values());
}

Rgb LightResponses::reflected(int node, std::span<const Rgb> radiance) const {
    Rgb sum;
    const auto r = reflected(node);
    for (int l = 0; l < lights_; ++l) sum += radiance[l] * r[l];
    return sum;
}

}  // namespace radiosity
