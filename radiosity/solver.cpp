#include "radiosity/solver.h"

#include "radiosity/detail/rng.h"
#include "radiosity/light_response.h"
#include "radiosity/machine_memory.h"
#include "radiosity/parallel.h"
#include "radiosity/stopwatch.h"
#include "radiosity/tree_walks.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace radiosity {

namespace {

/// The irradiance at every element node from what each node gathered itself (ownH for an
/// element, ownHv for a cluster), handed down as pushPull() hands it: element children
/// inherit their parent's total, and a polygon's root element takes what its cluster
/// ancestors gathered (fromClusters). Parents do not always precede their children in the
/// node array (an attached object's cluster), hence the explicit stack.
template <class OwnH, class OwnHv>
std::vector<Rgb> pushDown(const Hierarchy& h, const OwnH& ownH, const OwnHv& ownHv) {
    const auto& nodes = h.nodes;
    std::vector<Rgb> out(nodes.size());
    std::vector<int> stack{Hierarchy::kRoot};
    while (!stack.empty()) {
        const int node = stack.back();
        stack.pop_back();
        const Node& n = nodes[node];
        if (!n.isCluster()) {
            const bool root = n.parent < 0 || nodes[n.parent].isCluster();
            out[node] = ownH(node) + (root ? fromClusters(h, node, ownHv) : out[n.parent]);
        }
        for (int k = 0; k < n.childCount; ++k) stack.push_back(n.firstChild + k);
    }
    return out;
}

}  // namespace

HierarchicalSolver::HierarchicalSolver(Scene scene, SolverOptions options)
    : scene_(std::move(scene)),
      options_(std::move(options)),
      h_(scene_, options_.maxPolygonsPerCluster) {
    const double tHierarchy = secondsSince(constructed_);
    vis_ = std::make_unique<Visibility>(scene_);
    transfer_ = std::make_unique<TransferEvaluator>(h_, *vis_, options_.transfer);
    minArea_ = options_.minArea > 0 ? options_.minArea : 2e-5 * scene_.totalArea();
    maxMemory_ = options_.maxMemory > 0 ? options_.maxMemory : defaultMemoryBudget();
    maxLinks_ = options_.maxLinks > 0 ? options_.maxLinks : maxMemory_ / sizeof(Link);
    timing_.timeBuild = secondsSince(constructed_);
    if (options_.progress) {
        char msg[160];
        std::snprintf(msg, sizeof msg,
                      "hierarchy of %d polygons in %d face clusters: %.1f s; visibility: %.1f s",
                      static_cast<int>(scene_.polygons.size()), h_.faceClusterCount(), tHierarchy,
                      timing_.timeBuild - tHierarchy);
        report(msg);
    }
}

size_t defaultMemoryBudget() {
    const size_t memory = usableMemory();
    // Unknown (an unusual system): 4 GiB, what the 200 k-triangle room needs.
    if (memory == 0) return size_t{4} << 30;
    return static_cast<size_t>(0.4 * static_cast<double>(memory));
}

HierarchicalSolver::~HierarchicalSolver() = default;

void HierarchicalSolver::report(const std::string& msg) const {
    if (options_.progress) options_.progress(msg);
}

bool HierarchicalSolver::canSplit(int node) const {
    const Node& n = h_.nodes[node];
    if (!n.isLeaf()) return true;
    // Leaves of the scene as it was before the first dynamic insertion stay leaves: the
    // display interpolates over their corners.
    // Those under a new shadow are split by refineNewShadows() alone.
    if (frozenNodes_ > 0 && static_cast<size_t>(node) < frozenNodes_ && !shadowSplitting_)
        return false;
    return !n.isCluster() && n.area * 0.25 >= minArea_;
}

Link HierarchicalSolver::makeLink(int r, int s) const {
    Link link;
    link.receiver = r;
    link.source = s;
    link.F = transfer_->formFactor(r, s);
    return link;
}

HierarchicalSolver::Verdict HierarchicalSolver::oracle(const Link& link) const {
    const int r = link.receiver, s = link.source;
    const Node& R = h_.nodes[r];
    const Node& S = h_.nodes[s];
    // Skip what cannot carry light: a source element that neither emits nor reflects (a
    // light that is off). A receiver that reflects nothing (a lamp's face, a black surface)
    // keeps its links: they change no radiosity, and are accepted at once (its power
    // value is 0), but they say what it absorbs, so that the energy balance is whole.
    if (!S.isCluster() && S.rho.maxComponent() <= 0 && !S.emitting) return {Decision::drop, 0};
    // A cluster is never linked to itself: its self-interaction is refined into the pairs
    // of its children, or deferred (an element does not light itself: planar).
    if (r == s) return selfVerdict(r);
    // Links from lights go to elements, never to clusters (Loscos et al. 2000, §2.3 and
    // §5.2): shadow boundaries need per-element visibility of each source.
    if (S.isCluster() && S.emitting) return {Decision::splitSource, kForced};
    if (!S.isCluster() && S.emitting && R.isCluster()) return {Decision::splitReceiver, kForced};

    // BF criterion (HSA91), power form: rho_r B_s F A_r against epsilon times the emitted
    // power. F is the oracle's bound (conservative for clusters), A_r the receiver's area
    // that intercepts the source's light. For a receiver darker than the scene's mean the
    // threshold is lowered in proportion to its radiosity (receiverScale): the error that
    // matters to a picture is relative to what the receiver shows (Gibson & Hubbold 1997,
    // perceptually driven radiosity), and a display that divides a photo by the light
    // (Loscos et al. 1999, Eq. (2)) turns an absolute error in a dim corner into a large
    // error in its reflectance.
    const double threshold = powerThreshold_ * receiverScale(r);
    const double F = transfer_->bound(r, s, link.F);
    // Near field, the receiver's area facing the source's centre says little (a box's side
    // facing away from the floor's centre still sees half the floor): all of it counts.
    const double Ar = F > kFarField ? R.area : transfer_->receiverArea(r, s);
    // Weighed by what the camera sees of the receiver (Smits, Arvo & Salesin 1992).
    // With perLightOracle, B_s is the largest of the source's per-light radiosities,
    // each scaled to the power of all lights together (updateLightShares).
    // Off, B_s as it is (a sky's coefficient may light with either sign).
    const double Bs =
        lightShareB_.empty() ? S.B.maxComponent() : std::max(S.B.maxComponent(), lightShareB(s));
    const double value = R.rho.maxComponent() * Bs * F * Ar * importanceOf(r);

    // A link with a cluster end stands for its contents by one direction and one disc
    // (transfer.h): good only in the far field. Where the source may subtend a wide
    // angle (its bound F above kFarField), surfaces of other orientations see parts of
    // it that the centre's direction misses: refine at a tenth of the power threshold
    // (not at any power: the neighbouring clusters of one finely cut wall touch, yet
    // exchange next to nothing).
    const bool farField = !(R.isCluster() || S.isCluster()) || F <= kFarField ||
                          !(value > kNearFieldPower * threshold);
    if (farField && !(value > threshold)) return {Decision::accept, value};

    const bool splitR = canSplit(r), splitS = canSplit(s);
    if (!splitR && !splitS) return {Decision::accept, value};
    if (R.isCluster() || S.isCluster()) {
        // Of two clusters the larger one is opened. Of a cluster and an element, the
        // cluster, unless it is a surface (its faces within a cone narrower than
        // kSurfaceCone: none faces away from another) and the element is the larger: the
        // element is split then (Smits, Arvo & Greenberg 1994: the end that subtends the
        // larger angle). Opening every cluster first linked a 36 m^2 wall to 79 k triangles
        // of a chandelier one by one, and every point of the wall gathered them all; a
        // cluster of faces turned every way (a lamp's shade, inside and out) must still be
        // opened, or it sends its bright side's light out through its dark one.
        if (R.isCluster() && S.isCluster())
            return {R.radius >= S.radius ? Decision::splitReceiver : Decision::splitSource, value};
        const auto elementFirst = [this](const Node& cluster, const Node& element,
                                         bool canSplitIt) {
            return canSplitIt && h_.coneAngle(cluster) < kSurfaceCone &&
                   element.radius > kElementFirstRatio * cluster.radius;
        };
        if (R.isCluster())
            return {elementFirst(R, S, splitS) ? Decision::splitSource : Decision::splitReceiver,
                    value};
        return {elementFirst(S, R, splitR) ? Decision::splitReceiver : Decision::splitSource,
                value};
    }
    if (!splitR) return {Decision::splitSource, value};
    if (!splitS) return {Decision::splitReceiver, value};
    // Of two elements, split the larger: it subtends the larger angle from the other
    // (F_rs > F_sr <=> A_s > A_r by reciprocity).
    return {R.area >= S.area ? Decision::splitReceiver : Decision::splitSource, value};
}

double HierarchicalSolver::ambientIrradiance(double emitted) const {
    // Cohen, Chen, Wallace & Greenberg 1988, the ambient term: the mean irradiance of a
    // closed room of total area A and mean reflectance rho, Phi / (A (1 - rho)).
    const Node& root = h_.nodes[Hierarchy::kRoot];
    const double absorbed = 1.0 - std::min(root.rho.maxComponent(), kMaxAmbientReflectance);
    return root.area > 0 ? emitted / (root.area * absorbed) : 0.0;
}

HierarchicalSolver::Verdict HierarchicalSolver::selfVerdict(int node) const {
    const Node& R = h_.nodes[node];
    if (!R.isCluster()) return {Decision::drop, kForced};
    // A lamp inside: its links must reach elements (below), and only the split finds them.
    // Outside solve() (dynamic updates) every self-interaction is split, as they need.
    if (R.emitting || !deferSelf_) return {Decision::splitReceiver, kForced};
    double B = R.B.maxComponent();
    if (timing_.refineRounds == 0)
        B = std::max(B, R.rho.maxComponent() * ambientIrradiance_);  // nothing gathered yet
    const double value =
        R.rho.maxComponent() * B * R.area * selfTransferBound(h_.coneAngle(R)) * importanceOf(node);
    if (!(value > powerThreshold_ * receiverScale(node))) return {Decision::defer, value};
    return {Decision::splitReceiver, value};
}

double HierarchicalSolver::receiverScale(int r) const {
    if (!(options_.darkFloor < 1) || !(meanB_ > 0)) return 1.0;
    // A link's light is pushed to every leaf below its receiver, and its error matters to
    // the dimmest of them: a wall's element that spans a bright arm of an L-shaped room and
    // the corner into its dark one, weighed by its mean, accepted the coarse links whose
    // error lit the dark arm 1.65 times too bright (bench/leak_l_room; 1.52 so). A node
    // made since the last measure (a split) has its own radiosity, its parent's. A cluster
    // keeps its mean: what it gathers reaches its contents by their orientation (its
    // directional irradiance), not pushed alike to every leaf, and its dimmest leaf is
    // nearly always a face in contact (a box's bottom on the floor).
    const Node& R = h_.nodes[static_cast<size_t>(r)];
    double B = R.B.maxComponent();
    if (!R.isCluster() && static_cast<size_t>(r) < dimB_.size())
        B = std::min(B, static_cast<double>(dimB_[r]));
    return std::clamp(B / meanB_, options_.darkFloor, 1.0);
}

void HierarchicalSolver::measureDimmestLeaves() {
    // Per polygon, its element tree (receiverScale reads elements only; clusters keep +inf).
    const auto& nodes = h_.nodes;
    dimB_.assign(nodes.size(), std::numeric_limits<float>::infinity());
    const auto dimmestBelow = [&](const auto& self, int n) -> float {
        const Node& e = nodes[static_cast<size_t>(n)];
        float dimmest = std::numeric_limits<float>::infinity();
        if (e.isLeaf()) {
            if (!e.emitting && e.rho.maxComponent() > 0)
                dimmest = static_cast<float>(e.B.maxComponent());
        } else {
            for (int k = 0; k < e.childCount; ++k)
                dimmest = std::min(dimmest, self(self, e.firstChild + k));
        }
        return dimB_[static_cast<size_t>(n)] = dimmest;
    };
    parallelFor(h_.polygonRoot.size(), 256, [&](size_t p) {
        if (h_.polygonRoot[p] >= 0) dimmestBelow(dimmestBelow, h_.polygonRoot[p]);
    });
}

double HierarchicalSolver::lightShareB(int s) const {
    if (lightShareB_.empty()) return 0;
    // A node made since the shares were measured: its nearest ancestor's (a child's
    // radiosity starts as its parent's too).
    while (s >= 0 && static_cast<size_t>(s) >= lightShareB_.size()) s = h_.nodes[s].parent;
    return s >= 0 ? static_cast<double>(lightShareB_[static_cast<size_t>(s)]) : 0.0;
}

void HierarchicalSolver::updateLightShares() {
    lightShareB_.clear();
    const size_t K = scene_.lights.size();
    if (!(options_.perLightOracle > 0) || K < 2) return;
    // The lights' responses on the links of the last round: the refinement that follows
    // sees where each light's own light goes (a shaded lamp's light leaves its shade by a
    // bounce inside; links refined for the sum of a strong and a weak lamp's light stay
    // coarse where only the weak one's passes, and a light edit exposes them).
    const auto t0 = Clock::now();
    const LightResponses R(*this);
    const auto& nodes = h_.nodes;
    const auto lightB = [&](size_t n, size_t l) {
        const Rgb b = scene_.lights[l].radiance * R.reflected(static_cast<int>(n))[l];
        // A sky's coefficient lights with either sign: its magnitude is what is carried.
        return std::max({std::abs(b.r), std::abs(b.g), std::abs(b.b)});
    };
    std::vector<double> own(K, 0.0);
    double all = 0;
    for (size_t n = 0; n < nodes.size() && R.covers(static_cast<int>(n)); ++n) {
        const Node& e = nodes[n];
        if (e.isCluster() || !e.isLeaf() || !(e.rho.maxComponent() > 0)) continue;
        for (size_t l = 0; l < K; ++l) {
            const double p = lightB(n, l) * e.area;
            own[l] += p;
            all += p;
        }
    }
    if (!(all > 0)) return;
    // k_l: a light with a hundredth of the power has its links weighed as if it had all of
    // it, up to perLightOracle (a light that hardly reaches anything is not refined to the
    // accuracy of the lamps that light the room: the cost stays bounded).
    std::vector<double> scale(K, 0.0);
    for (size_t l = 0; l < K; ++l)
        scale[l] = own[l] > 0 ? std::min(all / own[l], options_.perLightOracle) : 0.0;
    lightShareB_.assign(nodes.size(), 0.0f);
    parallelFor(nodes.size(), 4096, [&](size_t n) {
        if (!R.covers(static_cast<int>(n))) return;
        double b = 0;
        for (size_t l = 0; l < K; ++l) b = std::max(b, scale[l] * lightB(n, l));
        lightShareB_[n] = static_cast<float>(b);
    });
    char msg[96];
    std::snprintf(msg, sizeof msg, "  per-light oracle: %zu lights' responses, %.1f s", K,
                  secondsSince(t0));
    report(msg);
}

void HierarchicalSolver::pushLightLinksToLeaves(size_t from) {
    std::vector<Link> old(links_.begin() + static_cast<std::ptrdiff_t>(from), links_.end());
    links_.truncate(from);
    links_.reserve(from + old.size() * 2);
    std::vector<Link> stack;
    std::vector<size_t> pending;  // links whose visibility is still to be evaluated
    for (const Link& l : old) {
        stack.push_back(l);
        while (!stack.empty()) {
            Link link = stack.back();
            stack.pop_back();
            const Node& S = h_.nodes[link.source];
            const Node& R = h_.nodes[link.receiver];
            if (!(S.emitting && !S.isCluster()) || R.isLeaf()) {
                if (needsVisibility(link)) pending.push_back(links_.size());
                links_.push_back(link);
                continue;
            }
            passive_.push_back(link);
            const int me = static_cast<int>(passive_.size()) - 1;
            for (int k = R.childCount - 1; k >= 0; --k) {
                const int rc = R.firstChild + k;
                if (!transfer_->facing(rc, link.source)) continue;
                stack.push_back(childLink(link, me, rc, link.source));
            }
        }
    }
    evaluateVisibility(pending);
}

std::span<const Link> HierarchicalSolver::linksOf(int node) const {
    return links_.of(node);
}

std::vector<Rgb> HierarchicalSolver::gatherDown(const std::function<Rgb(int)>& value, bool bounded,
                                                bool uncorrected) const {
    const auto& nodes = h_.nodes;
    std::vector<Rgb> H(nodes.size()), Hd(nodes.size());
    std::vector<DirectionalIrradiance> Hv(h_.clusterFields.size());  // by cluster slot
    parallelFor(links_.receiverCount(), 64, [&](size_t i) {
        const int r = links_.receiver(i);
        const Node& R = nodes[r];
        for (int k = links_.start(i); k < links_.start(i + 1); ++k) {
            const Link& l = links_[k];
            const Node& S = nodes[l.source];
            double V = l.V;
            if (uncorrected && l.corrected && R.lightCorrection > 0) V /= R.lightCorrection;
            const Rgb h = value(l.source) * (l.F * V);
            if (R.isCluster())
                Hv[R.clusterSlot].add(h, h_.toFrame(R, linkDirection(R, S)));
            else if (reflects(S))
                H[r] += h;
            else
                Hd[r] += h;
        }
    });
    std::vector<Rgb> out = pushDown(
        h_, [&](int n) -> const Rgb& { return H[n]; },
        [&](int n) -> const DirectionalIrradiance& { return Hv[nodes[n].clusterSlot]; });
    const std::vector<Rgb> direct = pushDown(
        h_, [&](int n) -> const Rgb& { return Hd[n]; },
        [](int) -> const DirectionalIrradiance& {
            static const DirectionalIrradiance none;
            return none;
        });
    for (size_t n = 0; n < nodes.size(); ++n) {
        const bool leaf = !nodes[n].isCluster() && nodes[n].isLeaf();
        out[n] = direct[n] + out[n] * (bounded && leaf ? nodes[n].gatherScale : 1.0);
    }
    return out;
}

void HierarchicalSolver::throwNotConverged(int sweeps, double power, double delta) const {
    // Name the leaf whose radiosity is largest relative to the brightest emitter: where
    // light piles up.
    int worst = -1;
    double worstB = -1;
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        const Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        const double b = (e.B - e.E).maxComponent();
        if (!(b <= worstB)) {  // NaN first
            worstB = b;
            worst = static_cast<int>(n);
        }
    }
    std::string where = "no element";
    if (worst >= 0) {
        const Node& e = h_.nodes[worst];
        const Polygon& p = scene_.polygons[e.polygon];
        const std::vector<Rgb> G = gatherDown([](int) { return Rgb::gray(1.0); }, true);
        where = "element " + std::to_string(worst) + " of polygon " + std::to_string(e.polygon) +
                (p.object >= 0 ? " (object '" + scene_.objects[p.object] + "')" : "") +
                ": reflected radiosity " + std::to_string(worstB) + ", reflectance " +
                std::to_string(e.rho.maxComponent()) + ", its links' form factors sum to " +
                std::to_string(G[worst].maxComponent());
    }
    char head[256];
    std::snprintf(head, sizeof head,
                  "radiosity did not converge after %d gather/push-pull sweeps (total power "
                  "%.6g, still changing by %.3g per sweep); largest: ",
                  sweeps, power, delta);
    throw SolverError(head + where);
}

int HierarchicalSolver::gatherPushPull() {
    // Jacobi sweeps converge geometrically, P_k -> P with ratio q (about the mean
    // reflectance). Stopping when the last change is small is not enough for rho -> 1:
    // the error left is about delta q / (1 - q). That estimate, with q measured from two
    // successive changes, is what must fall below `tolerance` (relative).
    if (!(sourcePower() > 0)) {
        // No light on: the solution is B = 0 (E = 0 everywhere). Sweeps would only decay
        // towards it geometrically, never meeting a relative tolerance.
        for (Node& n : h_.nodes) n.H = n.Hd = Rgb{};
        for (ClusterFields& c : h_.clusterFields) c.Hv = DirectionalIrradiance{};
        pushPullAll();
        return 1;
    }
    double previous = -1, previousDelta = -1;
    int count = 0;
    while (true) {
        const double power = sweep();
        ++count;
        if (!std::isfinite(power)) throwNotConverged(count, power, power);
        if (previous >= 0) {
            const double delta = std::abs(power - previous);
            double q = previousDelta > 0 ? delta / previousDelta : 0.5;
            q = std::min(q, 0.999);  // guard: a stalled or growing change gives a huge bound
            const double remaining = delta * q / (1.0 - q);
            if (delta <= options_.tolerance * std::abs(power) &&
                remaining <= options_.tolerance * std::abs(power))
                break;
            if (count >= options_.maxSweeps) throwNotConverged(count, power, delta);
            previousDelta = delta;
        }
        previous = power;
    }
    return count;
}

void HierarchicalSolver::solve() {
    updateDirectIrradiance();
    const double emitted = sourcePower();
    if (powerThreshold_ <= 0) setPowerThreshold();
    if (!started_) {
        links_.clear();
        Link root;
        root.receiver = root.source = Hierarchy::kRoot;
        links_.push_back(root);
        started_ = true;
    }
    if (!(emitted > 0)) {
        // No light: every radiosity is zero. Nothing to refine.
        for (Node& n : h_.nodes) n.H = n.Hd = Rgb{};
        for (ClusterFields& c : h_.clusterFields) c.Hv = DirectionalIrradiance{};
        pushPullAll();
        return;
    }
    if (!emitterLights_.empty()) pushPullAll();  // B of the lit leaves, for the first oracle
    const auto start = Clock::now();
    lastProgress_ = start;
    // A later solve() (the reflectance rounds) refines nothing more once the time is out.
    Clock::time_point deadline = options_.refineUntil;
    if (options_.refineSeconds > 0)
        deadline = std::min(deadline, secondsAfter(start, options_.refineSeconds));
    if (deadline != Clock::time_point::max())
        refineDeadline_ = timeBudgetReached_ ? start : deadline;
    measureSeenBeforeRefining();
    ambientIrradiance_ = ambientIrradiance(emitted);
    deferSelf_ = true;
    transfer_->setShaftTests(true);
    shaftsBeforeSolve_ = {transfer_->counters.shaftTests.load(),
                          transfer_->counters.shaftEmpty.load()};
    for (int round = 0; round < options_.maxRefineRounds; ++round) {
        auto t0 = Clock::now();
        // Each light's own light on the last round's links (none before the first gather;
        // nothing to refine once the time is out).
        if (options_.perLightOracle > 0 && timing_.refineRounds > 0 && !timeBudgetReached_)
            updateLightShares();
        const size_t refined = refineAll();
        const double tRefined = secondsSince(t0);
        stopShaftTestsThatDoNotPay();
        // Settled: the round refined (almost) nothing. A round that refines fewer than
        // kSettled of the links changes the solution by less than the links it leaves, each
        // just above the threshold, can; another round (1.8 s on 1.6 M links) is not worth it.
        const bool changed = changedInRefine_;
        // Past the deadline, another round would refine nothing and only gather again.
        const bool late =
            refineDeadline_ != Clock::time_point::max() && Clock::now() >= refineDeadline_;
        if (late && changed) timeBudgetReached_ = true;
        const bool settled =
            !changed || timeBudgetReached_ || late ||
            static_cast<double>(refined) <= kSettled * static_cast<double>(links_.size());
        const bool last = round + 1 == options_.maxRefineRounds || settled;
        if (last && options_.forceLightLinksToLeaves) pushLightLinksToLeaves();
        links_.index();
        normaliseLamps();
        const auto tBound = Clock::now();
        boundGather(0, /*balance=*/last);  // the sends once the links are final
        const double tBounded = secondsSince(tBound);
        timing_.timeRefine += secondsSince(t0);
        updateDirectIrradiance();  // the leaves the round made
        ++timing_.refineRounds;
        const auto tGather = Clock::now();
        const int sweeps = gatherPushPull();
        const double tGathered = secondsSince(tGather);
        if (!seenImportance_.empty() && !importanceBounced_) {
            updateImportance(/*bounce=*/true);
            importanceBounced_ = true;
        }
        char msg[256];
        std::snprintf(msg, sizeof msg,
                      "refine round %d: %zu links, %d leaves, %d sweeps, %.1f s (links %.1f s, "
                      "energy bound %.1f s, gather %.1f s)%s",
                      round + 1, links_.size(), h_.leafCount(), sweeps, secondsSince(start),
                      tRefined, tBounded, tGathered,
                      timeBudgetReached_ ? " (time budget reached)"
                      : budgetReached_   ? " (refinement budget reached)"
                                         : "");
        report(msg);
        if (settled) break;
    }
    deferSelf_ = false;
    transfer_->setShaftTests(true);              // dynamic updates test every shaft
    refineDeadline_ = Clock::time_point::max();  // dynamic updates refine without it
    lightShareB_.clear();  // and on the total light (an object's links; the shares are stale)
}

void HierarchicalSolver::stopShaftTestsThatDoNotPay() {
    if (!deferSelf_ || !transfer_->shaftTests()) return;  // only in solve()'s rounds, once
    const uint64_t tests = transfer_->counters.shaftTests.load() - shaftsBeforeSolve_[0];
    const uint64_t empty = transfer_->counters.shaftEmpty.load() - shaftsBeforeSolve_[1];
    if (shaftTestsPay(tests, empty)) return;
    transfer_->setShaftTests(false);
    char msg[200];
    std::snprintf(msg, sizeof msg,
                  "shaft tests off for the rest of this solve: %llu of its first %llu shafts were "
                  "empty (below %g %%); rays alone decide visibility",
                  static_cast<unsigned long long>(empty), static_cast<unsigned long long>(tests),
                  100 * options_.shaftPayoff);
    report(msg);
}

bool HierarchicalSolver::shaftTestsPay(uint64_t tests, uint64_t empty) const {
    // Shaft tests (Haines & Wallace 1991). An empty shaft makes a link VISIBLE without rays,
    // and its children too; a shaft that holds anything costs its walk down the hierarchy
    // and then the rays all the same. In an open or simple room a fifth of the shafts are
    // empty (the bundled scenes: 4-26 %, at most a few tens of thousands of tests). In a furnished
    // hall almost none is: 625 of 7.9 M on a 393 k-face stair hall, where the walks were a quarter
    // of the refinement's time (bench/RESULTS.md, 2026-11-30, twenty-fifth session). Few tests
    // decide nothing.
    return tests < kShaftSample ||
           static_cast<double>(empty) >= options_.shaftPayoff * static_cast<double>(tests);
}

void HierarchicalSolver::addLinksFromSource(int node) {
    changedInRefine_ = false;
    refineLinks({makeLink(Hierarchy::kRoot, node)});
}

void HierarchicalSolver::setLightRadiance(int light, const Rgb& radiance) {
    std::vector<Rgb> all(scene_.lights.size());
    for (size_t l = 0; l < all.size(); ++l) all[l] = scene_.lights[l].radiance;
    all.at(light) = radiance;
    setLightRadiances(all);
}

void HierarchicalSolver::setLightRadiances(std::span<const Rgb> radiance) {
    if (radiance.size() != scene_.lights.size())
        throw std::invalid_argument("setLightRadiances: one radiance per light expected");
    for (size_t l = 0; l < radiance.size(); ++l) scene_.lights[l].radiance = radiance[l];
    h_.updateEmittance(scene_);
    sumDirectIrradiance();
    if (!started_) return;
    addMissingLightLinks();
    gatherPushPull();
}

bool HierarchicalSolver::addMissingLightLinks() {
    // A light that was off when the links were refined has none: refine its own.
    std::vector<char> linked(scene_.polygons.size(), 0);
    for (const Link& l : links_) {
        const Node& S = h_.nodes[l.source];
        if (!S.isCluster()) linked[S.polygon] = 1;
    }
    bool added = false;
    for (const Light& light : scene_.lights) {
        if (!(light.radiance.maxComponent() > 0)) continue;
        for (int p : light.polygons) {
            if (linked[p]) continue;
            if (powerThreshold_ <= 0) setPowerThreshold();
            addLinksFromSource(h_.polygonRoot[p]);
            added = true;
        }
    }
    if (added) {
        if (options_.forceLightLinksToLeaves) pushLightLinksToLeaves();
        links_.index();
        normaliseLamps();
        boundGather(0, /*balance=*/true);
    }
    return added;
}

void HierarchicalSolver::ensureLightLinks() {
    if (!started_) return;
    // Links are refined for every light as if all were on at radiance 1 (each light then
    // weighs in the power threshold as it would in a solve with it on); the radiances
    // come back afterwards, and the solution is gathered again only if links were added.
    std::vector<Rgb> radiance(scene_.lights.size());
    for (size_t l = 0; l < radiance.size(); ++l) {
        radiance[l] = scene_.lights[l].radiance;
        scene_.lights[l].radiance = Rgb::gray(1.0);
    }
    h_.updateEmittance(scene_);
    const bool added = addMissingLightLinks();
    for (size_t l = 0; l < radiance.size(); ++l) scene_.lights[l].radiance = radiance[l];
    h_.updateEmittance(scene_);
    if (added) gatherPushPull();
}

Rgb HierarchicalSolver::radiosityAt(int polygon, const Vec3& x) const {
    return h_.nodes[h_.locateLeaf(polygon, x)].B;
}

Rgb HierarchicalSolver::irradianceAt(int polygon, const Vec3& x) const {
    const int leaf = h_.locateLeaf(polygon, x);
    const Vec3& normal = h_.nodes[leaf].normal;
    Rgb H, Hd;
    for (int n = leaf; n >= 0; n = h_.nodes[n].parent) {
        const Node& a = h_.nodes[n];
        H += a.isCluster() ? h_.Hv(a).onto(h_.toFrame(a, normal)) : a.H;
        Hd += a.isCluster() ? Rgb{} : a.Hd;
    }
    return Hd + H * h_.nodes[leaf].gatherScale;
}

void HierarchicalSolver::setReflectance(int polygon, const Rgb& rho) {
    scene_.polygons.at(polygon).rho = rho;
    std::vector<int> stack{h_.polygonRoot[polygon]};
    while (!stack.empty()) {
        Node& n = h_.nodes[stack.back()];
        stack.pop_back();
        n.rho = rho;
        for (int k = 0; k < n.childCount; ++k) stack.push_back(n.firstChild + k);
    }
}

SolverStats HierarchicalSolver::stats() const {
    SolverStats s = timing_;
    s.clusters = h_.clusterCount();
    s.elements = h_.elementCount();
    s.leaves = h_.leafCount();
    s.links = static_cast<int>(links_.size());
    for (const Link& l : links_) {
        if (l.type == VisibilityType::visible) ++s.linksVisible;
        if (l.type == VisibilityType::invisible) ++s.linksInvisible;
        if (l.type == VisibilityType::partial) ++s.linksPartial;
    }
    s.passiveLinks = static_cast<int>(passive_.size());
    s.rays = transfer_->counters.rays.load();
    s.formFactors = transfer_->counters.formFactors.load();
    s.shaftTests = transfer_->counters.shaftTests.load();
    s.shaftEmpty = transfer_->counters.shaftEmpty.load();
    s.emittedPower = scene_.emittedPower() + directPower_;
    // Energy balance: what each leaf gathered in the last sweep.
    const std::vector<Rgb> H = pushDown(
        h_, [&](int n) -> const Rgb& { return h_.nodes[n].H; },
        [&](int n) -> const DirectionalIrradiance& { return h_.Hv(h_.nodes[n]); });
    const std::vector<Rgb> Hd = pushDown(
        h_, [&](int n) -> const Rgb& { return h_.nodes[n].Hd; },
        [](int) -> const DirectionalIrradiance& {
            static const DirectionalIrradiance none;
            return none;
        });
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        const Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf()) continue;
        s.absorbedPower +=
            (Rgb::gray(1.0) - e.rho) * (Hd[n] + e.Hx + H[n] * e.gatherScale) * e.area;
        s.radiosityPower += e.B * e.area;
    }
    s.boundedLeaves = boundedLeaves_;
    s.maxGather = maxGather_;
    s.budgetReached = budgetReached_ || timeBudgetReached_;
    s.polygons = static_cast<int>(scene_.polygons.size());
    s.faceClusters = h_.faceClusterCount();
    s.timeBudgetReached = timeBudgetReached_;
    s.memoryBytes = memoryUsed(0);
    s.maxLinks = maxLinks_;
    s.maxMemory = maxMemory_;
    s.selfLinksDeferred = static_cast<int>(deferredSelf_.size());
    return s;
}

void HierarchicalSolver::setElementReflectance(int leaf, const Rgb& rho) {
    Node& n = h_.nodes.at(leaf);
    if (n.isCluster() || !n.isLeaf())
        throw std::invalid_argument("setElementReflectance: not a leaf element");
    n.rho = rho;
}

int HierarchicalSolver::lightOfNode(int node) const {
    const Node& n = h_.nodes[node];
    return n.isCluster() ? -1 : scene_.polygons[n.polygon].light;
}

std::vector<HierarchicalSolver::LightExchange> HierarchicalSolver::lightExchange(int node) const {
    std::vector<LightExchange> out(scene_.lights.size());
    for (const Link& l : linksOf(node)) {
        const int light = lightOfNode(l.source);
        if (light < 0) continue;
        out[light].F += l.F;
        out[light].FV += l.F * static_cast<double>(l.V);
    }
    return out;
}

bool HierarchicalSolver::splitForLights(int leaf,
                                        std::vector<std::vector<LightExchange>>* children) {
    const Node& n = h_.nodes.at(leaf);
    if (n.isCluster() || !n.isLeaf() || !canSplit(leaf)) return false;
    // The leaf's links from lights leave the active list (order kept: the gather sums
    // each receiver's links in list order, so results stay independent of threads).
    SplitRecord rec;
    rec.leaf = leaf;
    std::vector<Link> kept;
    kept.reserve(links_.size());
    for (size_t i = 0; i < links_.size(); ++i) {
        const Link& l = links_[i];
        if (l.receiver == leaf && lightOfNode(l.source) >= 0) {
            rec.removed.push_back(l);
            rec.at.push_back(i);
        } else {
            kept.push_back(l);
        }
    }
    links_.replace(std::move(kept));
    h_.subdivide(leaf);
    const Node& parent = h_.nodes[leaf];
    if (children) children->assign(4, std::vector<LightExchange>(scene_.lights.size()));
    for (const Link& old : rec.removed) {
        const double scale = lampScale(old);
        passive_.push_back(old);
        const int me = static_cast<int>(passive_.size()) - 1;
        for (int k = 0; k < parent.childCount; ++k) {
            const int rc = parent.firstChild + k;
            if (!transfer_->facing(rc, old.source)) continue;
            Link c = lightChildLink(old, me, rc, scale);
            finishLightChildLink(c);
            links_.push_back(c);
            if (children) {
                LightExchange& e = (*children)[k][lightOfNode(old.source)];
                e.F += c.F;
                e.FV += c.F * static_cast<double>(c.V);
            }
        }
    }
    lastSplit_ = std::move(rec);
    return true;
}

void HierarchicalSolver::unsplit(int leaf) {
    const Node& n = h_.nodes.at(leaf);
    if (lastSplit_.leaf != leaf || n.childCount != 4 ||
        n.firstChild + 4 != static_cast<int>(h_.nodes.size()))
        throw std::logic_error("unsplit: only the last splitForLights can be cancelled");
    const int first = n.firstChild;
    links_.eraseIf([&](const Link& l) { return l.receiver >= first; });
    passive_.resize(passive_.size() - lastSplit_.removed.size());
    for (size_t k = 0; k < lastSplit_.removed.size(); ++k)  // ascending indices
        links_.insert(lastSplit_.at[k], lastSplit_.removed[k]);
    h_.unsubdivide(leaf);
    lastSplit_ = {};
}

void HierarchicalSolver::scaleLightLinks(int node, double c) {
    if (!(c >= 0) || !std::isfinite(c))
        throw std::invalid_argument("scaleLightLinks: the correction must be finite and >= 0");
    h_.nodes[node].lightCorrection *= c;
    const std::span<const Link> run = links_.of(node);
    if (run.empty()) return;
    const size_t first = static_cast<size_t>(run.data() - links_.all().data());
    for (size_t k = first; k < first + run.size(); ++k)
        if (lightOfNode(links_[k].source) >= 0) {
            Link& l = links_.mutableAt(k);
            l.V = static_cast<float>(static_cast<double>(l.V) * c);
            l.corrected = true;
        }
}

double HierarchicalSolver::lampScale(const Link& l) const {
    if (lightOfNode(l.source) < 0) return 1.0;
    const double unscaled = transfer_->formFactor(l.receiver, l.source);
    return unscaled > 0 ? l.F / unscaled : 1.0;
}

Link HierarchicalSolver::lightChildLink(const Link& l, int parentIndex, int r, double scale) const {
    // What the parent link carried beyond its geometry goes to the child: the lamp's
    // normalisation (normaliseLamps scaled its F) and the receiver's link correction (the
    // child inherits its parent's Node::lightCorrection).
    Link c = childLink(l, parentIndex, r, l.source);
    c.F *= scale;
    c.corrected = l.corrected;
    return c;
}

void HierarchicalSolver::finishLightChildLink(Link& c) const {
    if (needsVisibility(c))
        visibilityAgain(c);
    else if (c.corrected)
        c.V = static_cast<float>(static_cast<double>(c.V) * h_.nodes[c.receiver].lightCorrection);
}

void HierarchicalSolver::visibilityAgain(Link& l) const {
    transfer_->visibility(l);
    if (l.corrected)
        l.V = static_cast<float>(static_cast<double>(l.V) * h_.nodes[l.receiver].lightCorrection);
}

}  // namespace radiosity
