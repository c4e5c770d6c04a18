// Dynamic objects of the hierarchical solver: insertion, removal and motion of virtual
// objects and lights (Drettakis & Sillion 1997, "Interactive update of global illumination
// using a line-space hierarchy", as used by Loscos, Drettakis & Robert 2000, §5.1-5.2).
//
// The links form a tree by their `parent` (the passive link each was refined from): the
// line-space hierarchy. An object changes visibility only inside the shafts it cuts, and a
// link's segments lie in the convex hull of its parent's two boxes, which its shaft
// contains: when the object misses a passive link's shaft it misses every link below it.
// The walk from the top links therefore reaches exactly the links the object may block,
// at the cost of the shafts tested on the way.
//
// Removal restores a snapshot taken at insertion (links, B, H), so that insertion followed
// by removal gives back the solution bit for bit; the work of a move (shaft tests, rays,
// new links) is only that of the old and the new position.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "radiosity/detail/shaft.h"
#include "radiosity/parallel.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"

namespace radiosity {

namespace {

/// The links' refinement tree (Link::parent): the children of each passive link, encoded
/// p >= 0 (passive) and ~a < 0 (active), in [start[p], start[p + 1]), and the roots.
struct LinkTree {
    std::vector<int> start, child, roots;

    LinkTree(const std::vector<Link>& passive, const ActiveLinks& active) {
        const int P = static_cast<int>(passive.size());
        const int A = static_cast<int>(active.size());
        start.assign(static_cast<size_t>(P) + 2, 0);
        for (int p = 0; p < P; ++p) {
            if (passive[p].parent >= 0)
                ++start[passive[p].parent + 2];
            else
                roots.push_back(p);
        }
        for (int a = 0; a < A; ++a) {
            if (active[a].parent >= 0)
                ++start[active[a].parent + 2];
            else
                roots.push_back(~a);
        }
        for (int p = 0; p < P; ++p) start[p + 2] += start[p + 1];
        child.resize(static_cast<size_t>(start[P + 1]));
        for (int p = 0; p < P; ++p)
            if (passive[p].parent >= 0) child[start[passive[p].parent + 1]++] = p;
        for (int a = 0; a < A; ++a)
            if (active[a].parent >= 0) child[start[active[a].parent + 1]++] = ~a;
        // start[p] .. start[p + 1] are now the children of p.
    }

    /// Marks the active links below passive link p.
    void markActiveBelow(int p, std::vector<char>& marked) const {
        std::vector<int> stack{p};
        while (!stack.empty()) {
            const int id = stack.back();
            stack.pop_back();
            if (id < 0) {
                marked[~id] = 1;
                continue;
            }
            for (int k = start[id]; k < start[id + 1]; ++k) stack.push_back(child[k]);
        }
    }
};

}  // namespace

void HierarchicalSolver::cutLinks(const Bounds3& box, int object, DynamicUpdate& report,
                                  bool revive) {
    auto t0 = Clock::now();
    CutLinks found = findCutLinks(box, object, report, revive);
    report.timeShafts += secondsSince(t0) - found.timeVisibility;

    // Visibility of the cut links again, in parallel (each link's rays are seeded by its
    // nodes, so the order does not matter).
    t0 = Clock::now();
    std::vector<int>& cut = found.cut;
    std::erase_if(cut, [&](int a) { return found.erased[a] != 0; });
    const uint64_t raysBefore = transfer_->counters.rays.load();
    parallelFor(cut.size(), 8, [&](size_t i) {
        Link& l = links_.mutableAt(cut[i]);
        if (revive || !l.corrected) {
            // An insertion adds its shadow to what the photo showed: a link corrected by
            // real-shadow removal keeps its correction.
            visibilityAgain(l);
            return;
        }
        // A removal: where the object blocked part of the link, the shadow the correction
        // was measured in is (partly) gone, and so is the correction; elsewhere the
        // correction was for another blocker and stays. (The rays are seeded by the link's
        // nodes: an unchanged visibility is the same number.)
        const double corr = h_.nodes[l.receiver].lightCorrection;
        const double before = corr > 0 ? static_cast<double>(l.V) / corr : 0.0;
        transfer_->visibility(l);
        if (static_cast<double>(l.V) > before * (1 + 1e-6) + 1e-6)
            l.corrected = false;
        else
            l.V = static_cast<float>(static_cast<double>(l.V) * corr);
    });
    report.linksCut += static_cast<int>(cut.size());
    // The leaf elements under each cut light link's receiver: a link may end above the
    // leaves (an element subdivided for other links, a cluster far from the lamp); every
    // leaf below it may have lost or regained the lamp's direct light.
    std::vector<int> stack;
    for (int a : cut) {
        const Link& l = links_[a];
        if (lightOfNode(l.source) < 0) continue;
        stack.assign(1, l.receiver);
        while (!stack.empty()) {
            const int n = stack.back();
            stack.pop_back();
            const Node& R = h_.nodes[n];
            if (!R.isCluster() && R.isLeaf()) {
                report.shadowLeaves.push_back(n);
                continue;
            }
            for (int c = 0; c < R.childCount; ++c) stack.push_back(R.firstChild + c);
        }
    }
    // Erasing keeps the receiver order; the revived links go after it.
    if (report.linksReactivated > 0) {
        std::vector<Link> kept;
        kept.reserve(links_.size());
        for (size_t a = 0; a < found.erased.size(); ++a)
            if (!found.erased[a]) kept.push_back(links_[a]);
        links_.replace(std::move(kept));
    }
    for (const Link& c : found.revived) links_.push_back(c);
    report.rays += transfer_->counters.rays.load() - raysBefore;
    report.timeVisibility += secondsSince(t0) + found.timeVisibility;
}

HierarchicalSolver::CutLinks HierarchicalSolver::findCutLinks(const Bounds3& box, int object,
                                                              DynamicUpdate& report, bool revive) {
    // The link tree walked from its roots: a link whose shaft misses the object's box
    // keeps its whole subtree as it is (Drettakis & Sillion 1997).
    const LinkTree tree(passive_, links_);
    CutLinks out;
    out.erased.assign(links_.size(), 0);
    const auto isObjectNode = [&](int node) {
        const Node& n = h_.nodes[node];
        return !n.isCluster() && scene_.polygons[static_cast<size_t>(n.polygon)].object == object;
    };
    std::vector<int> stack(tree.roots.rbegin(), tree.roots.rend());
    while (!stack.empty()) {
        const int id = stack.back();
        stack.pop_back();
        const Link& L = id >= 0 ? passive_[id] : links_[~id];
        if (id >= 0 && L.retired) continue;
        if (isObjectNode(L.receiver) || isObjectNode(L.source)) continue;
        ++report.shaftTests;
        const Shaft shaft(h_.nodes[L.receiver].bounds, h_.nodes[L.source].bounds);
        if (!shaft.mayIntersect(box)) continue;
        if (id < 0) {
            out.cut.push_back(~id);
            continue;
        }
        // A passive link between two elements (not from a light: those stay at the leaves)
        // that the object now blocks entirely carries nothing: as refineLinks() would keep it
        // unrefined, it becomes active again in place of its subtree (Drettakis & Sillion
        // 1997: passive links are reactivated at no cost, F is kept).
        const Node& R = h_.nodes[L.receiver];
        const Node& S = h_.nodes[L.source];
        if (revive && !R.isCluster() && !S.isCluster() && L.receiver != L.source && !S.emitting) {
            const auto tv = Clock::now();
            Link c = L;
            transfer_->visibility(c, /*thorough=*/true);
            out.timeVisibility += secondsSince(tv);
            if (c.type == VisibilityType::invisible) {
                passive_[id].retired = true;
                inserted_.back().retired.push_back(id);
                tree.markActiveBelow(id, out.erased);
                out.revived.push_back(c);
                ++report.linksReactivated;
                continue;
            }
        }
        for (int k = tree.start[id + 1] - 1; k >= tree.start[id]; --k)
            stack.push_back(tree.child[k]);
    }
    return out;
}

void HierarchicalSolver::linkObject(int cluster, int oldRoot, DynamicUpdate& report) {
    const auto t0 = Clock::now();
    const uint64_t raysBefore = transfer_->counters.rays.load();
    const size_t first = links_.size();
    // 1. What the object gathers from the scene, then its radiosity from those links alone
    //    (the refinement of what it shoots needs it: the oracle weighs B_s).
    Link gather = makeLink(cluster, oldRoot);
    refineLinks({gather});
    for (size_t i = first; i < links_.size(); ++i) gatherInto(links_[i]);
    pushPull(cluster, Rgb{}, Rgb{});
    // 2. What it shoots into the scene, and its light onto itself.
    Link shoot = makeLink(oldRoot, cluster);
    refineLinks({shoot, makeLink(cluster, cluster)});
    if (options_.forceLightLinksToLeaves) pushLightLinksToLeaves(first);
    report.linksNew += static_cast<int>(links_.size() - first);
    for (size_t i = first; i < links_.size(); ++i) {
        const Link& l = links_[i];
        const Node& R = h_.nodes[l.receiver];
        if (lightOfNode(l.source) >= 0 && !R.isCluster() && R.isLeaf() &&
            static_cast<size_t>(l.receiver) < frozenNodes_)
            report.shadowLeaves.push_back(l.receiver);  // a new light's links
    }
    report.rays += transfer_->counters.rays.load() - raysBefore;
    report.timeLinks += secondsSince(t0);
}

HierarchicalSolver::Insertion HierarchicalSolver::snapshot() const {
    Insertion rec;
    rec.links = links_.all();
    rec.passive = passive_.size();
    rec.polygons = scene_.polygons.size();
    rec.objects = scene_.objects.size();
    rec.lights = scene_.lights.size();
    rec.B.reserve(h_.nodes.size());
    rec.Bsent.reserve(h_.nodes.size());
    rec.scales.reserve(h_.nodes.size());
    rec.H.reserve(h_.nodes.size());
    rec.Hd.reserve(h_.nodes.size());
    for (const Node& n : h_.nodes) {
        rec.B.push_back(n.B);
        rec.Bsent.push_back(n.Bsent);
        rec.scales.push_back({n.gatherScale, n.sendScale});
        rec.H.push_back(n.H);
        rec.Hd.push_back(n.Hd);
    }
    rec.Hv.reserve(h_.clusterFields.size());
    for (const ClusterFields& c : h_.clusterFields) rec.Hv.push_back(c.Hv);
    rec.frozenNodes = frozenNodes_;
    return rec;
}

int HierarchicalSolver::insertObject(const std::string& name, std::vector<Polygon> polygons,
                                     const Rgb* lightRadiance, DynamicUpdate* reportOut) {
    if (!started_) throw std::logic_error("insertObject: solve() first");
    if (polygons.empty()) throw std::invalid_argument("insertObject: the object has no polygon");
    links_.index();
    DynamicUpdate report;
    Insertion rec = snapshot();
    rec.name = name;
    rec.light = lightRadiance != nullptr;
    if (lightRadiance) rec.radiance = *lightRadiance;
    if (frozenNodes_ == 0) frozenNodes_ = h_.nodes.size();

    // The scene: a new object, maybe a new light.
    const int object = static_cast<int>(scene_.objects.size());
    scene_.objects.push_back(name);
    int light = -1;
    if (lightRadiance) {
        light = static_cast<int>(scene_.lights.size());
        Light l;
        l.name = name;
        l.radiance = *lightRadiance;
        scene_.lights.push_back(l);
    }
    const int first = static_cast<int>(scene_.polygons.size());
    Bounds3 box;
    for (Polygon& p : polygons) {
        p.object = object;
        p.light = light;
        if (light >= 0) {
            p.rho = Rgb{};  // an emitting face reflects nothing (scene.h)
            scene_.lights[light].polygons.push_back(static_cast<int>(scene_.polygons.size()));
        }
        box.extend(p.bounds());
        scene_.polygons.push_back(p);
    }
    const std::span<const Polygon> added(scene_.polygons.data() + first, polygons.size());
    std::vector<Rgb> emittance(polygons.size());
    for (size_t i = 0; i < polygons.size(); ++i)
        emittance[i] = scene_.emittance(first + static_cast<int>(i));
    inserted_.push_back(std::move(rec));
    int oldRoot = -1;
    const int cluster =
        h_.attachObject(added, first, emittance, options_.maxPolygonsPerCluster, &oldRoot);
    inserted_.back().visGroup = vis_->addPolygons(added, first);
    // The root's links (if any: usually refined away) now belong to its copy.
    links_.relabel([&](Link& l) {
        if (l.receiver == Hierarchy::kRoot) l.receiver = oldRoot;
        if (l.source == Hierarchy::kRoot) l.source = oldRoot;
    });
    for (Link& l : passive_) {
        if (l.receiver == Hierarchy::kRoot) l.receiver = oldRoot;
        if (l.source == Hierarchy::kRoot) l.source = oldRoot;
    }

    cutLinks(box, object, report);
    const size_t firstNode = static_cast<size_t>(oldRoot);
    linkObject(cluster, oldRoot, report);
    links_.index();
    // A virtual light delivers its power as a lamp of the scene does (normaliseLamps);
    // its links are new, so removal takes the scaling away with them.
    if (light >= 0) normaliseLamps(first);
    // The leaves under the new shadows follow them (2000, Fig. 24(a)): after the lamps'
    // normalisation, which the split links inherit.
    refineNewShadows(report);
    // The object's own leaves are bounded and balanced (their sends and gathers), and so
    // are the scene's leaves whose view the object may change: what they see is measured
    // again (a floor under a box sees the box's underside where it saw open space). The
    // rest keep their scales.
    const std::vector<int> reseen = remeasureSeenNear(cluster, firstNode);
    boundGather(firstNode, /*balance=*/true, &reseen);
    refreshEmitterLight(report);
    inserted_.back().shadowLeaves = report.shadowLeaves;

    const auto t0 = Clock::now();
    report.sweeps = gatherPushPull();
    report.timeGather += secondsSince(t0);
    if (reportOut) *reportOut = std::move(report);
    return object;
}

void HierarchicalSolver::refineNewShadows(DynamicUpdate& report) {
    if (!options_.newShadowSplits || frozenNodes_ == 0) return;
    const auto t0 = Clock::now();
    const uint64_t raysBefore = transfer_->counters.rays.load();
    std::vector<int> leaves;
    for (int leaf : report.shadowLeaves)
        if (static_cast<size_t>(leaf) < frozenNodes_) leaves.push_back(leaf);
    std::sort(leaves.begin(), leaves.end());
    leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
    links_.index();
    // Level by level (a split moves the leaf's links from lights to its children, and the
    // list of links is rebuilt once per level, not once per split): the leaves crossed by a
    // shadow boundary are split, their children's links from lights get their visibility
    // (in parallel), and the children still crossed by it are split at the next level.
    std::vector<std::pair<int, int>> level;  // (leaf, splits still allowed below it)
    for (int leaf : leaves)
        if (crossedByShadow(leaf)) level.emplace_back(leaf, options_.newShadowSplits(leaf));
    shadowSplitting_ = true;
    struct Reset {
        bool& flag;
        ~Reset() { flag = false; }
    } reset{shadowSplitting_};
    while (!level.empty()) {
        std::vector<Link> fresh;
        std::vector<std::pair<int, int>> split;
        for (const auto& [leaf, depth] : level) {
            if (depth <= 0 || !canSplit(leaf)) continue;
            const std::span<const Link> run = links_.of(leaf);
            std::vector<Link> old;
            for (const Link& l : run)
                if (lightOfNode(l.source) >= 0) old.push_back(l);
            h_.subdivide(leaf);
            const Node& n = h_.nodes[leaf];
            for (int k = 0; k < n.childCount; ++k) {
                // A child sees about what its parent saw (same plane, a quarter of the
                // size): the energy bound's measure is kept rather than cast again on every
                // move of an object.
                h_.nodes[n.firstChild + k].seen = n.seen;
                h_.nodes[n.firstChild + k].seenError = n.seenError;
            }
            for (const Link& l : old) {
                passive_.push_back(l);
                const int me = static_cast<int>(passive_.size()) - 1;
                const double scale = lampScale(l);
                for (int k = 0; k < n.childCount; ++k)
                    if (transfer_->facing(n.firstChild + k, l.source))
                        fresh.push_back(lightChildLink(l, me, n.firstChild + k, scale));
            }
            split.emplace_back(leaf, depth);
        }
        if (split.empty()) break;
        report.shadowSplits += static_cast<int>(split.size());
        std::vector<char> isSplit(h_.nodes.size(), 0);
        for (const auto& sd : split) isSplit[static_cast<size_t>(sd.first)] = 1;
        links_.eraseIf([&](const Link& l) {
            return isSplit[static_cast<size_t>(l.receiver)] && lightOfNode(l.source) >= 0;
        });
        parallelFor(fresh.size(), 16, [&](size_t i) { finishLightChildLink(fresh[i]); });
        for (const Link& c : fresh) links_.push_back(c);
        links_.index();
        level.clear();
        for (const auto& [leaf, depth] : split) {
            const Node& n = h_.nodes[leaf];
            for (int k = 0; k < n.childCount; ++k)
                if (depth > 1 && crossedByShadow(n.firstChild + k))
                    level.emplace_back(n.firstChild + k, depth - 1);
        }
    }
    report.rays += transfer_->counters.rays.load() - raysBefore;
    report.timeLinks += secondsSince(t0);
}

bool HierarchicalSolver::crossedByShadow(int leaf) const {
    const Node& n = h_.nodes[leaf];
    if (n.isCluster() || !n.isLeaf()) return false;
    // A shadow boundary crosses the leaf where one of its links from a light is PARTIAL
    // (Loscos et al. 2000, §2.3); an umbra or a lit leaf has nothing to follow. Lights
    // that give the leaf less than kShadowMinShare of its unoccluded direct light are left
    // out: their shadow does not show.
    double total = 0;
    const std::span<const Link> run = links_.of(leaf);
    for (const Link& l : run) {
        const int light = lightOfNode(l.source);
        if (light >= 0) total += l.F * scene_.lights[light].radiance.maxComponent();
    }
    for (const Link& l : run) {
        const int light = lightOfNode(l.source);
        if (light >= 0 && l.type == VisibilityType::partial &&
            l.F * scene_.lights[light].radiance.maxComponent() >= kShadowMinShare * total)
            return true;
    }
    return false;
}

std::vector<int> HierarchicalSolver::remeasureSeenNear(int cluster, size_t firstNode) {
    const Node& obj = h_.nodes[cluster];
    return remeasureSeenNear(obj.centre, obj.radius, firstNode, -1);
}

std::vector<int> HierarchicalSolver::remeasureSeenNear(const Vec3& c, double r, size_t firstNode,
                                                       int object) {
    // The object's bounding sphere (centre c, radius r) covers at most r^2 / (r^2 + g^2) of
    // a leaf's cosine-weighted hemisphere, g the gap between the sphere and the leaf's own
    // bounding sphere (a disc facing the leaf squarely bounds the sphere's silhouette).
    // Leaves where that can exceed kSeenChange, with the sphere not wholly behind them,
    // are measured again. A leaf that saw a surface in every direction (seen 1, closed
    // rooms) keeps its measure: a closed object only hides fronts behind its own fronts,
    // and taking one out shows what it hid.
    std::vector<int> leaves;
    for (size_t n = 0; n < firstNode; ++n) {
        const Node& e = h_.nodes[n];
        if (e.isCluster() || !e.isLeaf() || !(e.seen >= 0) || e.seen >= 1) continue;
        if (object >= 0 && scene_.polygons[static_cast<size_t>(e.polygon)].object == object)
            continue;
        const Vec3 d = c - e.centre;
        if (glm::dot(e.normal, d) < -r) continue;  // behind the leaf's plane
        const double gap = std::max(0.0, glm::length(d) - r - e.radius);
        if (r * r > kSeenChange * (r * r + gap * gap)) leaves.push_back(static_cast<int>(n));
    }
    for (int leaf : leaves)
        inserted_.back().reseen.push_back({leaf, h_.nodes[leaf].seen, h_.nodes[leaf].seenError});
    measureSeen(leaves);
    return leaves;
}

void HierarchicalSolver::removeLastObject(DynamicUpdate* report) {
    if (inserted_.empty()) throw std::logic_error("removeLastObject: no object inserted");
    Insertion rec = std::move(inserted_.back());
    inserted_.pop_back();
    if (rec.removed >= 0) {
        // A real object taken out: it occludes and reflects again.
        vis_->showPolygons(rec.hidden);
        for (size_t n = 0; n < rec.rho.size(); ++n) h_.nodes[n].rho = rec.rho[n];
    } else {
        vis_->removePolygons(rec.visGroup);
        h_.detachLastObject();
    }
    // Leaves that the change split (an earlier virtual object's: only the scene's are
    // frozen) are leaves again; their children were made after the snapshot.
    h_.truncateElements(rec.B.size());
    links_.replace(std::move(rec.links));
    passive_.resize(rec.passive);
    if (rec.removed < 0) {
        const int oldRoot = static_cast<int>(rec.B.size());  // the root's copy: the next node
        for (Link& l : passive_) {
            if (l.receiver == oldRoot) l.receiver = Hierarchy::kRoot;
            if (l.source == oldRoot) l.source = Hierarchy::kRoot;
        }
    }
    for (int p : rec.retired) passive_[p].retired = false;
    scene_.polygons.resize(rec.polygons);
    scene_.objects.resize(rec.objects);
    scene_.lights.resize(rec.lights);
    for (size_t n = 0; n < rec.B.size(); ++n) {
        h_.nodes[n].B = rec.B[n];
        h_.nodes[n].Bsent = rec.Bsent[n];
        h_.nodes[n].gatherScale = rec.scales[n][0];
        h_.nodes[n].sendScale = rec.scales[n][1];
        h_.nodes[n].H = rec.H[n];
        h_.nodes[n].Hd = rec.Hd[n];
    }
    for (size_t c = 0; c < rec.Hv.size(); ++c) h_.clusterFields[c].Hv = rec.Hv[c];
    for (const auto& [leaf, seen, seenError] : rec.reseen) {
        h_.nodes[leaf].seen = seen;
        h_.nodes[leaf].seenError = seenError;
    }
    frozenNodes_ = rec.frozenNodes;
    links_.index();
    // The emitters' direct light as before the change: measured again with the same rays
    // (seeded by node) and the same geometry, it is what it was.
    if (!emitterLights_.empty()) updateDirectIrradiance(/*all=*/true);
    if (report) report->shadowLeaves = std::move(rec.shadowLeaves);
}

void HierarchicalSolver::moveLastObject(std::vector<Polygon> polygons, DynamicUpdate* report) {
    if (inserted_.empty() || lastIsRemoval())
        throw std::logic_error("moveLastObject: no object inserted last");
    const std::string name = inserted_.back().name;
    const bool light = inserted_.back().light;
    const Rgb radiance = inserted_.back().radiance;
    const auto t0 = Clock::now();
    DynamicUpdate removal;
    removeLastObject(&removal);
    const double removeTime = secondsSince(t0);
    DynamicUpdate insertion;
    insertObject(name, std::move(polygons), light ? &radiance : nullptr, &insertion);
    insertion.timeLinks += removeTime;
    for (int leaf : removal.shadowLeaves) insertion.shadowLeaves.push_back(leaf);
    std::sort(insertion.shadowLeaves.begin(), insertion.shadowLeaves.end());
    insertion.shadowLeaves.erase(
        std::unique(insertion.shadowLeaves.begin(), insertion.shadowLeaves.end()),
        insertion.shadowLeaves.end());
    if (report) *report = std::move(insertion);
}

}  // namespace radiosity
