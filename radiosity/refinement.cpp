// The refinement of HierarchicalSolver (radiosity/solver.h): the links of largest oracle
// value split first from a priority queue, within the budgets of links, memory and time
// (--time-budget: the deadline, what a queued link still costs, what the leaves see
// measured before it), and the accepted links' visibility. The oracle itself, solve()'s
// rounds and the gather stay in solver.cpp.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "radiosity/deadline.h"
#include "radiosity/parallel.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"

namespace radiosity {

size_t HierarchicalSolver::memoryUsed(size_t queued) const {
    return h_.nodes.size() * sizeof(Node) +
           (links_.size() + passive_.size() + queued) * sizeof(Link) +
           queued * sizeof(double);  // the queue's keys
}

bool HierarchicalSolver::withinBudget(size_t queued) const {
    return links_.size() + passive_.size() + queued < maxLinks_ && memoryUsed(queued) < maxMemory_;
}

void HierarchicalSolver::refineLinks(std::vector<Link> seeds) {
    // Refinement by priority (Stamminger et al. 1999; Gibson & Hubbold 1996): the link of
    // largest oracle value is refined first, so that when the budget of links and memory
    // runs out, what is left unrefined is where the oracle's error is smallest. Ties are
    // broken by the nodes' ids: the order, and so the node ids made by subdivision, do
    // not depend on anything but the input.
    struct Entry {
        double value;
        Link link;
    };
    const auto lower = [](const Entry& a, const Entry& b) {
        if (a.value != b.value) return a.value < b.value;
        if (a.link.receiver != b.link.receiver) return a.link.receiver > b.link.receiver;
        return a.link.source > b.link.source;
    };
    std::vector<Entry> queue;
    queue.reserve(seeds.size());
    const auto push = [&](const Link& l) {
        queue.push_back({oracle(l).value, l});
        std::push_heap(queue.begin(), queue.end(), lower);
    };
    for (const Link& l : seeds) push(l);
    seeds = {};
    std::vector<size_t> pending;  // accepted links whose visibility is still to be evaluated
    const auto accept = [&](const Link& l) {
        if (needsVisibility(l)) pending.push_back(links_.size());
        links_.push_back(l);
        // The accepted links' visibility in batches as they come: each link's rays are its
        // own (seeded by its nodes), so the result is the same, and the time budget then
        // knows what a link's visibility costs early and owes little at its deadline (all
        // at the end, a stair hall's 1.1 M links overran it by 8 s on a loaded machine).
        if (pending.size() >= kVisibilityBatch) {
            evaluateVisibility(pending);
            pending.clear();
        }
    };
    lastClock_ = {};
    while (!queue.empty()) {
        ++pops_;
        std::pop_heap(queue.begin(), queue.end(), lower);
        Link link = queue.back().link;
        queue.pop_back();
        const Verdict v = oracle(link);
        if (v.decision == Decision::drop) continue;
        if (v.decision == Decision::defer) {
            deferredSelf_.push_back(link.receiver);
            continue;
        }
        const bool forced = v.value == kForced;
        if (v.decision == Decision::accept) {
            accept(link);
            continue;
        }
        if (!forced && (!withinBudget(queue.size()) || outOfTime(queue.size(), pending.size()))) {
            // Out of budget: keep the link as it is; what is still queued has a smaller
            // oracle value. A cluster's self-interaction cannot be a link: it waits.
            budgetReached_ = true;
            if (link.receiver == link.source)
                deferredSelf_.push_back(link.receiver);
            else
                accept(link);
            continue;
        }
        const Node& R0 = h_.nodes[link.receiver];
        const Node& S0 = h_.nodes[link.source];
        if (!forced && !R0.isCluster() && !S0.isCluster()) {
            // A link between two elements that is entirely blocked carries nothing: no need
            // to refine it. That verdict must rest on all maxRays rays, not on the first few
            // (4 blocked rays happen 1 time in 10 for a link that is 45 % visible). Cluster
            // links are refined whatever their sampled visibility.
            const bool evaluated = !needsVisibility(link);
            const bool sure = link.shaftEmpty || link.rays >= transfer_->options().maxRays;
            if (!evaluated || (link.type == VisibilityType::invisible && !sure))
                transfer_->visibility(link, /*thorough=*/true);
            if (link.type == VisibilityType::invisible) {
                links_.push_back(link);
                continue;
            }
        }
        changedInRefine_ = true;
        passive_.push_back(link);  // Drettakis & Sillion 1997: keep it for dynamic updates
        const int me = static_cast<int>(passive_.size()) - 1;

        const int r = link.receiver, s = link.source;
        if (v.decision == Decision::splitReceiver && h_.nodes[r].isLeaf()) h_.subdivide(r);
        if (v.decision == Decision::splitSource && h_.nodes[s].isLeaf()) h_.subdivide(s);
        const Node& R = h_.nodes[r];
        const Node& S = h_.nodes[s];
        const auto child = [&](int rc, int sc) {
            if (!transfer_->facing(rc, sc)) return;
            push(childLink(link, me, rc, sc));
        };
        if (r == s) {
            // A cluster linked to itself: every ordered pair of its children.
            for (int i = 0; i < R.childCount; ++i)
                for (int j = 0; j < R.childCount; ++j) child(R.firstChild + i, R.firstChild + j);
        } else if (v.decision == Decision::splitReceiver) {
            for (int i = 0; i < R.childCount; ++i) child(R.firstChild + i, s);
        } else {
            for (int j = 0; j < S.childCount; ++j) child(r, S.firstChild + j);
        }
    }
    evaluateVisibility(pending);
}

bool HierarchicalSolver::outOfTime(size_t queued, size_t pending) {
    // Only solve() sets a deadline: dynamic updates refine their own links in full, also
    // after a preparation whose refinement ran out of time.
    if (refineDeadline_ == Clock::time_point::max()) return false;
    if (timeBudgetReached_) return true;
    if (clockCalls_++ % kClockStride != 0) return false;
    const auto now = Clock::now();
    // What a queued link costs once the time is out: it is popped and judged by the oracle
    // once more, then accepted, and its visibility evaluated. The pops' cost is measured
    // here, over the kClockStride pops since the last reading (those that split do more
    // than a drain's pops: the estimate errs on the early side). Not across calls of
    // refineLinks: the time between them is spent elsewhere.
    if (lastClock_ != Clock::time_point{} && pops_ > lastPops_)
        secondsPerPop_ = std::chrono::duration<double>(now - lastClock_).count() /
                         static_cast<double>(pops_ - lastPops_);
    lastClock_ = now;
    lastPops_ = pops_;
    // What is queued or accepted still needs its visibility: stop while there is time for
    // it (a real stair hall's second round queued 37 M links in a minute).
    const double owedSeconds = static_cast<double>(queued) * (secondsPerPop_ + secondsPerLink_) +
                               static_cast<double>(pending) * secondsPerLink_;
    if (secondsAfter(now, owedSeconds) >= refineDeadline_) {
        timeBudgetReached_ = true;
        report("time budget of the refinement reached: " + std::to_string(links_.size()) +
               " links accepted, " + std::to_string(queued) + " left as they are");
        return true;
    }
    if (std::chrono::duration<double>(now - lastProgress_).count() >= kProgressSeconds) {
        lastProgress_ = now;
        char msg[160];
        std::snprintf(msg, sizeof msg, "  refining: %zu links accepted, %zu queued, %d leaves",
                      links_.size(), queued, h_.leafCount());
        report(msg);
    }
    return false;
}

Link HierarchicalSolver::childLink(const Link& parent, int parentIndex, int r, int s) const {
    Link c = makeLink(r, s);
    c.parent = parentIndex;
    // The shaft of two sub-volumes lies in the convex hull of the parents' volumes, which
    // held no occluder: the child is visible too.
    if (parent.shaftEmpty) setShaftEmpty(c);
    return c;
}

void HierarchicalSolver::evaluateVisibility(const std::vector<size_t>& pending) {
    // Each link's rays come from a generator seeded by its two nodes: evaluating them in
    // parallel gives the same result as one by one. Only solve()'s rounds narrow a visible
    // link's cluster source (an option): a dynamic update measures its links as they are.
    const bool narrow = options_.narrowClusterSources && deferSelf_;
    const auto t0 = Clock::now();
    parallelFor(pending.size(), 16, [&](size_t i) {
        transfer_->visibility(links_.mutableAt(pending[i]), false, narrow);
    });
    if (pending.size() >= kLinksTimed)  // the time budget's estimate of what a link costs
        secondsPerLink_ = secondsSince(t0) / static_cast<double>(pending.size());
    // After a whole batch: the counts, and so the decision, do not depend on the threads.
    stopShaftTestsThatDoNotPay();
}

size_t HierarchicalSolver::refineAll() {
    changedInRefine_ = false;
    if (options_.darkFloor < 1) {
        // The mean radiosity the oracle weighs receivers against (0 before the first
        // gather: receiverScale is then 1).
        double sumBA = 0, sumA = 0;
        for (const Node& n : h_.nodes)
            if (n.isLeaf() && !n.isCluster() && !n.emitting && n.rho.maxComponent() > 0) {
                sumBA += n.B.maxComponent() * n.area;
                sumA += n.area;
            }
        meanB_ = sumA > 0 ? sumBA / sumA : 0;
        measureDimmestLeaves();
    }
    std::vector<Link> old = links_.take();
    links_.reserve(old.size() * 2);
    // Most links stay as they are: the oracle is asked for all of them in parallel, and
    // only those to refine go through the priority queue. Accepted links keep their order
    // (the gather sums each receiver's links in list order).
    std::vector<Decision> decision(old.size());
    parallelFor(old.size(), 4096, [&](size_t i) { decision[i] = oracle(old[i]).decision; });
    std::vector<Link> seeds;
    std::vector<size_t> pending;
    for (size_t i = 0; i < old.size(); ++i) {
        if (decision[i] == Decision::drop) continue;
        if (decision[i] == Decision::accept) {
            const Link& l = old[i];
            if (needsVisibility(l)) pending.push_back(links_.size());
            links_.push_back(l);
        } else {
            seeds.push_back(old[i]);
        }
    }
    old = {};
    // The self-interactions deferred so far, judged again with this round's radiosities.
    for (const int node : deferredSelf_) {
        Link self;
        self.receiver = self.source = node;
        seeds.push_back(self);
    }
    deferredSelf_.clear();
    evaluateVisibility(pending);
    const size_t refined = passive_.size();
    if (!seeds.empty()) refineLinks(std::move(seeds));
    return passive_.size() - refined;
}

void HierarchicalSolver::measureSeenBeforeRefining() {
    // What the leaves see (the energy bound's measurement, boundGather) is measured before
    // the refinement rather than after its first round: the same rays (each leaf's or face
    // cluster's own seed), but their time is then spent before the refinement's deadline is
    // weighed, not after it. On a real stair hall, 393 k leaves, it took 3-11 s, which
    // the first round used to overrun its deadline by. The lamps' faces are left to
    // normaliseLamps, which measures them more finely.
    std::vector<int> unmeasured;
    for (size_t n = 0; n < h_.nodes.size(); ++n) {
        const Node& e = h_.nodes[n];
        if (!e.isCluster() && e.isLeaf() && e.seen < 0 && !e.emitting)
            unmeasured.push_back(static_cast<int>(n));
    }
    if (unmeasured.empty()) return;
    const auto t0 = Clock::now();
    const bool whole = measureSeenUntilDeadline(unmeasured);
    if (unmeasured.size() >= kSeenReported || !whole) {
        char msg[200];
        std::snprintf(msg, sizeof msg,
                      "what %zu leaves see, measured for the energy bound: %.1f s%s",
                      unmeasured.size(), secondsSince(t0),
                      whole ? "" : " (time budget reached: the leaves not measured are unbounded)");
        report(msg);
    }
}

bool HierarchicalSolver::measureSeenUntilDeadline(const std::vector<int>& leaves) {
    // Each leaf's measurement is its own: cut at the refinement's deadline, the leaves
    // measured keep theirs and the others stay unmeasured (seen < 0), which the bound
    // leaves as they are (rowScale).
    return runUntil(refineDeadline_, [&] { measureSeenByPatch(leaves); });
}

}  // namespace radiosity
