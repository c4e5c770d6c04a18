// HierarchicalSolver: clustered hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991;
// Sillion 1995), as summarised in Loscos et al. 2000, §2.3.
//
// API
//   HierarchicalSolver solver(scene, options);  // builds clusters, elements, Embree BVH
//   solver.solve();                             // refine + gather/push-pull to convergence
//   solver.radiosityAt(polygon, x)              // B at a point (radiosity units)
//   solver.setLightRadiance(light, L);          // emittance edit: re-gather only
//   solver.stats()                              // counts and times per phase
//
// The top-level loop (solve()): starting from the root cluster linked to itself,
//   repeat { refine every link with the current B (BF oracle), largest error first, within
//            the budget; bound the gather; gather + push-pull until the total power
//            changes by less than `tolerance` } until a round refines no link, or so few
//            (at most kSettled = 0.1 % of them) that another round is not worth its cost.
// Then links whose source is a light are pushed down to the leaf elements (the 2000
// paper's shadow work needs them there).
//
// Energy bound. Each link's transfer is bounded (transfer.h), a cluster is never linked to
// itself, and a cluster hands what it gathers to each of its surfaces by that surface's
// orientation (directional_irradiance.h), so nothing gathers light it faces away from.
// Links of one receiver are still unoccluded estimates of sources that may hide one
// another, with sampled visibility, and a leaf also gathers through its parents' links
// (averaged over the parents): the sum G of the form factors above a leaf is right only to
// within those errors (1 +- 0.2 next to contact edges). What a leaf can gather at most is
// known, though: the fraction `seen` of its cosine-weighted hemisphere in which it sees the
// front of a surface (1 in a closed room), measured once per leaf by ray casting (64
// cosine-distributed rays, 256 where they disagree), less Gd, the exact form factors of
// its links to the lamps. So after each refinement the solver gathers a radiosity of 1
// from every source that reflects (G) and from every lamp (Gd), and moves each leaf's G
// into the interval seen - Gd +- 2 standard errors of the rays, never above 1 - Gd: first
// the leaves below each element of a polygon together, into the interval of their area
// mean, whose error is far smaller (a shortfall that a whole surface shares, each leaf's
// within its own error, is found there: groupRowScales), then each leaf alone; by
// scaling what the leaf gathers from reflecting sources (gatherScale, at most
// kMaxRenormalisation; stats().boundedLeaves counts the leaves moved by more than 5 %,
// stats().maxGather is the largest G). The form factors of every leaf then sum to at most
// 1: no leaf gathers more than a surface can, none loses what its links miss (a one-sided
// clamp at 1 would destroy the light of the half of the errors above 1, 9 % of the
// bundled room's power), and gather/push-pull contracts by the largest reflectance per
// sweep, so it converges for any rho < 1. Direct light from the lamps' faces (sources
// that do not reflect) is not scaled per receiver (the real-shadow correction scales
// those links on purpose, scaleLightLinks), but per lamp: the links from each emitting
// face are scaled so that it delivers its whole power to the surfaces it sees
// (normaliseLamps; the same rays measure what the face sees). A gather
// that still fails to converge (maxSweeps) stops with SolverError naming the element that did not
// settle.
//
// Self-interaction. A cluster is never linked to itself: a link needs two ends apart. Its
// self-interaction is refined into the pairs of its children when what it can carry,
//     rho B A F_self (times the camera's importance of the cluster),
// exceeds the oracle's threshold (below); otherwise it is deferred: kept aside and judged
// again in the next round, with the radiosities of that round's gather. F_self bounds the
// fraction of the cluster's light that lands on the cluster itself from its normal cone
// (half-angle t about axis a): light leaving a face of normal n (within t of a) towards
// direction d can reach a face of the cluster only from its front, so a.d < sin t, and
// n.d < sin t + |a - n| <= sin t + 2 sin(t/2) = c; the cosine-weighted share of n's
// hemisphere with n.d < c is c^2, so F_self <= min(1, c^2): 0 for a planar face cluster,
// 0.03 at 5 degrees. Before the first gather B is the cluster's reflectance times the
// ambient irradiance of a closed room, Phi / (A (1 - rho_mean)) (Cohen et al. 1988's
// ambient term), since nothing has gathered yet. Splitting every self-interaction to the
// bottom, as the method did before, made 1.13 M links on a real stair hall (262 k
// triangles) whatever the budget: O(input), most of them between the small triangles of
// one curved surface, whose exchange is far below the threshold. What a deferred cluster's
// surfaces miss of one another's light is below that threshold, and the energy bound
// below gives each leaf what it sees of the cluster back through the other links.
//
// Balance of what leaves send. Scaling the rows (what each leaf gathers) leaves the
// columns (what each leaf sends) as the links made them: the links are not reciprocal, a
// bright source whose coarse links under-deliver loses light, and a closed room absorbed
// only 97.6-99.3 % of what its lamps emit. So, once the links are final (the last round,
// and after new light links), each reflecting leaf m also has a send scale s_m: it sends
// B_m s_m through its links and those of its ancestors (Node::Bsent, the area mean of
// that below a node). What m then hands out, per unit of its power B_m A_m, is
//     C_m = s_m sum_{links r <- s, s above m} F V W_r / A_s,
// W_r the area of the receiver's leaves weighted by their gather scales (for a cluster
// receiver, by how much of the link's directional irradiance each surface takes). By
// reciprocity it must be what m sees. Rows and columns alternate, kBalanceIterations
// times (iterative proportional fitting: Sinkhorn 1967; interval targets, seen +- 2
// standard errors, on both), the sends held at a geometric mean of 1 (rows and columns
// fix only the products of the two scales), and the rows come last, so the contraction
// bound above holds whatever the columns reached. A closed room then absorbs 99.99 % of
// what its lamp emits (bench/closed_room). The final gather (final_gather.h) keeps the
// true radiosities: its per-point form factors do not have the links' errors that the
// send scales correct.
//
// Budget (Stamminger, Schirmacher, Slusallek & Seidel 1999): refinement stops splitting
// when the links (active, passive and queued) reach maxLinks or the nodes and links reach
// maxMemory bytes; what is left is accepted as it is, and stats().budgetReached says so.
// Splits the method cannot do without (a cluster's self-interaction, links from lights
// pushed down to elements) are made whatever the budget: they are O(lights x elements).
//
// Options and their units:
//   epsilon  BF refinement threshold, dimensionless: a link r <- s is refined when
//            rho_r * B_s * F * A_r > epsilon * (total emitted power), i.e. when the power it
//            would reflect exceeds that fraction of the power of all lights (max channel).
//            Typical 1e-4 (fine) .. 1e-2 (coarse). Scale-free: the same value means the
//            same accuracy in any room and any photo units.
//   minArea  smallest element area, m^2; 0 selects 2e-5 of the scene's total area.
//   tolerance  relative change of the total radiosity power (sum B A) between two
//            gather/push-pull sweeps below which the sweeps stop (typ. 1e-4).
//   maxLinks, maxMemory  the refinement budget (links; bytes of nodes and links); 0 selects
//            the default: maxMemory 40 % of usableMemory(), maxLinks what
//            fits in it.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "radiosity/active_links.h"
#include "radiosity/defaults.h"
#include "radiosity/detail/transfer.h"
#include "radiosity/emitter.h"
#include "radiosity/hierarchy.h"
#include "radiosity/link.h"
#include "radiosity/scene.h"
#include "radiosity/stopwatch.h"
#include "radiosity/visibility.h"

namespace radiosity {

/// A solve that cannot finish correctly: gather/push-pull that does not converge. The
/// message names the element that did not settle (polygon, object) and its gather sum.
struct SolverError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The default refinement budget: 40 % of the memory this process may count on
/// (usableMemory(), radiosity/machine_memory.h), in bytes.
size_t defaultMemoryBudget();

struct SolverOptions {
    double epsilon = kDefaultEpsilon;  ///< radiosity/defaults.h says why relight's is finer
    /// Relative accuracy where it is dark: a receiver whose dimmest leaf's radiosity is below
    /// the mean of the reflecting leaves has its threshold lowered in proportion, down to
    /// this fraction of epsilon (1: the plain BF criterion). See oracle(), receiverScale().
    double darkFloor = 1.0;
    /// Per-light refinement (issue 30, "light round corners"): from the second round on, a
    /// link is weighed by the largest of its source's radiosities from each light alone,
    /// each scaled by (all lights' reflected power / that light's), at most by this factor,
    /// as well as by the source's total radiosity; so a weak lamp's light is refined to the
    /// relative accuracy of the strong one's. 0: off (the BF criterion on the total light).
    /// See updateLightShares().
    double perLightOracle = 0;
    /// A VISIBLE link from a cluster gathers from the part of the cluster that its rays
    /// reached and every part not turned away from the receiver, F V kept (transfer.h,
    /// "Narrowed sources"), in solve()'s refinement. Off by default: on the stair hall it
    /// moved no edit beyond the spread of repeated runs and cost a few percent of the
    /// preparation (bench/RESULTS.md, 2026-11-28, fourteenth session); it lowers a shaded
    /// lamp's leak only (8.4 -> 6.2 %).
    bool narrowClusterSources = false;
    /// Shaft tests (Haines & Wallace 1991) go on in solve() while they pay: once a solve has
    /// made at least kShaftSample tests (checked after each batch of visibility evaluations
    /// and each round) and fewer than this fraction of its shafts were empty, they stop for
    /// the rest of that solve, and rays alone decide (the same verdicts: an empty shaft's
    /// rays all pass). 0: every shaft is tested.
    double shaftPayoff = 0.01;
    /// With setCameraSeen: the lowest share of the emitted power that the threshold
    /// follows (seenPowerShare()); 1: the plain criterion on all of it.
    double seenPowerFloor = 0.01;
    size_t maxLinks = 0;   ///< refinement budget in links (0: what fits in maxMemory)
    size_t maxMemory = 0;  ///< refinement budget in bytes (0: defaultMemoryBudget())
    /// Time budget of solve()'s refinement, seconds from solve()'s start (0: none). When it
    /// runs out, the link being refined and those still queued are accepted as they are
    /// (the largest oracle values were refined first), no later round refines, and the
    /// links from lights still go down to the leaves (the method needs them there).
    double refineSeconds = 0;
    /// The same as a time point (a command's TimeBudget, radiosity/stopwatch.h): no
    /// refinement goes on past it, whichever of the two comes first. The largest time
    /// point: none.
    Clock::time_point refineUntil = Clock::time_point::max();
    double minArea = 0;
    double tolerance = 1e-4;
    int maxSweeps = 2000;     ///< gather/push-pull sweeps per solve, a safety bound
    int maxRefineRounds = 8;  ///< refine/solve rounds
    int maxPolygonsPerCluster = 4;
    /// The emitters' direct light on a leaf (updateDirectIrradiance): the mean over this
    /// many stratified points of the element, each with directRays rays per emitter.
    int directPoints = 16;
    int directRays = 16;
    bool forceLightLinksToLeaves = true;
    /// Balance what each leaf sends as well as what it gathers (energy bound).
    bool balanceSends = true;
    TransferOptions transfer;
    /// New shadows (Loscos et al. 2000, §5.2 and Fig. 24(a); Drettakis & Sillion 1997): how
    /// many times a leaf of the scene (as it was at the first insertion) may be split where
    /// an inserted object or light makes its link from a light PARTIAL, so that the leaves
    /// follow the new shadow's boundary. Empty: never (the leaf keeps one averaged V).
    /// relight sets it to the display's split of each leaf (display pieces of a few pixels).
    std::function<int(int leaf)> newShadowSplits;
    /// Called with a one-line message at each phase of long work (may be empty).
    std::function<void(const std::string&)> progress;
};

struct SolverStats {
    int clusters = 0, elements = 0, leaves = 0;
    int polygons = 0, faceClusters = 0;  ///< the input's, and its face clusters (hierarchy.h)
    int links = 0, linksVisible = 0, linksInvisible = 0, linksPartial = 0;
    int passiveLinks = 0;  ///< links kept after being refined (Drettakis & Sillion 1997)
    /// Clusters whose self-interaction is left unrefined: what it can carry is below the
    /// oracle's threshold (HierarchicalSolver, "self-interaction")
    int selfLinksDeferred = 0;
    int refineRounds = 0, sweeps = 0;
    uint64_t rays = 0, formFactors = 0, shaftTests = 0, shaftEmpty = 0;
    double timeBuild = 0, timeRefine = 0, timeGather = 0, timePushPull = 0;  ///< seconds
    /// sum E A over lights (radiosity units x m^2), plus what the emitters deliver to the
    /// leaves (sum Hx A)
    Rgb emittedPower;
    Rgb absorbedPower;   ///< sum (1 - rho) H A over leaves
    Rgb radiosityPower;  ///< sum B A over leaves
    /// Energy bound: leaves whose gather was scaled by more than 5 % (seen / G), and the
    /// largest sum G of the form factors of the links above a leaf from sources that
    /// reflect.
    int boundedLeaves = 0;
    double maxGather = 1;
    bool budgetReached = false;          ///< refinement stopped at maxLinks / maxMemory / time
    bool timeBudgetReached = false;      ///< ... of them, at SolverOptions::refineSeconds
    size_t memoryBytes = 0;              ///< nodes and links (active and passive), bytes
    size_t maxLinks = 0, maxMemory = 0;  ///< the budget in force
};

/// What a dynamic update did (insertObject, removeLastObject, moveLastObject), and where
/// its time went.
struct DynamicUpdate {
    int shaftTests = 0;        ///< shafts of the link tree tested against the object's box
    int linksCut = 0;          ///< active links whose shaft the object's box cuts
    int linksReactivated = 0;  ///< passive links made active again (entirely blocked now)
    int linksNew = 0;          ///< links of the object itself
    uint64_t rays = 0;         ///< visibility rays cast
    int sweeps = 0;            ///< gather/push-pull sweeps
    /// Leaf elements whose links from a light the object's shaft cuts (old and new
    /// positions for a move): where the direct light may have changed.
    std::vector<int> shadowLeaves;
    /// Splits of the scene's leaves under new shadows (SolverOptions::newShadowSplits) kept.
    int shadowSplits = 0;
    double timeShafts = 0, timeVisibility = 0, timeLinks = 0, timeGather = 0;  ///< seconds
};

class HierarchicalSolver {
  public:
    HierarchicalSolver(Scene scene, SolverOptions options = {});
    ~HierarchicalSolver();

    /// Refines and solves from the current links (the first call starts from the root
    /// cluster linked to itself).
    void solve();
    /// Gather + push-pull sweeps on the existing links until converged; returns sweeps.
    int gatherPushPull();
    /// One gather over all links (H of every receiver node), then one push-pull.
    /// Returns the new total radiosity power (max channel).
    double sweep();

    /// Lights that are not emitting faces (radiosity/emitter.h: sun, point lamp, sky),
    /// appended to the scene's lights, one per component (Light::emitter), with the
    /// emitter's strengths as radiances. Their direct light enters as each leaf's direct
    /// irradiance Hx = sum_l L_l H_l, H_l the unit-strength irradiance of component l
    /// measured over the element with visibility; B = E + rho (Hd + Hx + H). What the
    /// leaves reflect of it is carried by the links like any light (gather/push-pull), and
    /// the refinement's oracle weighs it with the rest (its power threshold counts
    /// sum Hx A). Added before solve(), or followed by gatherPushPull(). Returns the index
    /// of its first light.
    int addEmitter(std::shared_ptr<const Emitter> emitter);
    /// Removes the lights from `first` on, which must all have an emitter (added by
    /// addEmitter after every inserted object is removed), and their direct light.
    void removeEmitterLights(int first);
    /// The solution's light: per node B, Bsent, H, Hd and Hx, per cluster Hv, and the
    /// lights' radiances (what a relighting session changes without changing the nodes).
    struct LightState {
        struct NodeLight {
            Rgb B, Bsent, H, Hd, Hx;
        };
        std::vector<NodeLight> nodes;
        std::vector<DirectionalIrradiance> Hv;  ///< by cluster slot
        std::vector<Rgb> radiance;
    };
    LightState lightState() const;
    /// Puts `state` back bit for bit, without gathering again (from the edited state a
    /// gather converges to within its tolerance of the old solution, not to it). The nodes
    /// and lights must be those it was taken with; throws std::logic_error otherwise.
    void restoreLightState(const LightState& state);
    /// Applies `edit` to the emitter of light `light` (any of its components; its strengths
    /// taken from their radiances), then as setLightEmitter. Throws as Emitter::apply.
    void editEmitter(int light, const EmitterEdit& edit);
    /// Gives the components of light `light`'s emitter a new one (moved, turned) and its
    /// strengths as their radiances; measures every leaf's H_l again and gathers again.
    /// Links and subdivision are kept (as setLightRadiance).
    void setLightEmitter(int light, std::shared_ptr<const Emitter> emitter);
    /// Measures H_l on the leaves that lack it (all with `all`), in parallel, each leaf's
    /// rays seeded by its node id (the same result with any thread count), and sums Hx.
    void updateDirectIrradiance(bool all = false);
    /// The scene's lights that have an emitter, in order (empty: faces only).
    const std::vector<int>& emitterLights() const { return emitterLights_; }
    /// Leaf `node`'s unit-strength direct irradiance of each of emitterLights(), as last
    /// measured (radiosity units per unit strength); empty without emitter lights.
    std::span<const double> directUnit(int node) const {
        const size_t J = emitterLights_.size();
        if (J == 0 || static_cast<size_t>(node) * J + J > Hunit_.size()) return {};
        return {Hunit_.data() + static_cast<size_t>(node) * J, J};
    }

    /// Emittance edit: keeps subdivision and links, re-gathers. A light that had no links
    /// (it was off when refined) gets its links refined first.
    void setLightRadiance(int light, const Rgb& radiance);
    /// The same for all lights at once (one radiance per light), with one re-gather.
    void setLightRadiances(std::span<const Rgb> radiance);
    /// Refines links for every light that has none (as if it were on, at radiance 1), so
    /// that any light can be switched on later; radiances are kept, and the solution is
    /// gathered again only if links were added.
    void ensureLightLinks();

    /// Dynamic objects (Drettakis & Sillion 1997, as used by Loscos et al. 2000, §5.1-5.2).
    /// Inserts `polygons` (world space, checked by makePolygon; their `object` and `light`
    /// fields are set here) as a new object named `name`, and, when `lightRadiance` is given,
    /// as a new light of that radiance (its faces then emit; rho is set to 0). Steps:
    ///  1. the object becomes a cluster under the root (Hierarchy::attachObject) and enters
    ///     the visibility BVH;
    ///  2. the link tree is walked from its top links; a link whose shaft (Haines & Wallace)
    ///     misses the object's box is skipped with all its subtree; an active link cut by it
    ///     gets its visibility again; a passive link between two elements that the object
    ///     now blocks entirely is made active again, replacing its subtree (as a solution
    ///     from scratch would keep it unrefined);
    ///  3. the object is linked to the scene by the refinement oracle: first the links it
    ///     gathers (so that its radiosity is known), then those it shoots and its own;
    ///     links from a light go down to leaf elements; the scene's leaves present at the
    ///     first insertion are not subdivided by it (the display's mesh stays as it is);
    ///  4. those of them whose links from a light are now PARTIAL (a new shadow's boundary
    ///     crosses them) are split, level by level, as SolverOptions::newShadowSplits
    ///     allows (Loscos et al. 2000, Fig. 24(a)); their links from the lights go to the
    ///     children with the lamp's normalisation and the link correction they carried;
    ///  5. gather/push-pull, warm-started from the current solution.
    /// Returns the object's index in scene().objects.
    int insertObject(const std::string& name, std::vector<Polygon> polygons,
                     const Rgb* lightRadiance = nullptr, DynamicUpdate* report = nullptr);
    /// Removes the object inserted last: scene, hierarchy, links, passive links, B and H
    /// are restored bit for bit as they were before its insertion. Throws std::logic_error
    /// when no object was inserted.
    void removeLastObject(DynamicUpdate* report = nullptr);
    /// Moves the object inserted last to `polygons` (the same faces, new positions):
    /// removal as above, then insertion at the new place; only links whose shafts the old
    /// or the new box cuts have their visibility evaluated again.
    void moveLastObject(std::vector<Polygon> polygons, DynamicUpdate* report = nullptr);
    /// Sets SolverOptions::newShadowSplits for the insertions to come (empty: none).
    void setNewShadowSplits(std::function<int(int leaf)> rule) {
        options_.newShadowSplits = std::move(rule);
    }
    /// Objects inserted and not removed (real objects taken out count as well).
    int insertedObjects() const { return static_cast<int>(inserted_.size()); }
    /// The scene's own polygons, those given to the constructor: scene().polygons before
    /// the first inserted object's.
    size_t scenePolygons() const {
        return inserted_.empty() ? scene_.polygons.size() : inserted_.front().polygons;
    }

    /// Real-object removal (Loscos et al. 1999, §4.4 and §5.3: "we delete every link ... of
    /// the removed object"): takes the scene's object `object` (an index of
    /// scene().objects; its polygons, none of them a lamp's face) out of the solution, as
    /// the last dynamic change. Steps:
    ///  1. its polygons stop occluding (Visibility::hidePolygons); its elements reflect
    ///     and send nothing (rho = B = 0) and every link to or from them goes;
    ///  2. the links whose shafts its box cuts get their visibility again, as for an
    ///     insertion (the light it blocked comes back); DynamicUpdate::shadowLeaves are the
    ///     leaves under the cut links from lights;
    ///  3. `seen` is measured again where the object filled much of a leaf's view, and the
    ///     energy bound is set again for those leaves and the receivers of the changed links;
    ///  4. gather/push-pull, warm-started.
    /// removeLastObject() brings it back, bit for bit. Throws std::invalid_argument for an
    /// index out of range, an object with no polygon or with a lamp's face, or one taken out
    /// already; std::logic_error before solve().
    void removeRealObject(int object, DynamicUpdate* report = nullptr);
    /// Whether the last dynamic change is a real object taken out (removeRealObject).
    bool lastIsRemoval() const { return !inserted_.empty() && inserted_.back().removed >= 0; }
    /// The scene's objects taken out and not brought back.
    std::vector<int> removedObjects() const;

    /// B at point x of polygon (radiosity units): the value of the leaf containing it.
    Rgb radiosityAt(int polygon, const Vec3& x) const;
    /// Irradiance H at point x of polygon (radiosity units): the sum of what the links of
    /// the leaf containing x and of all its ancestors gathered in the last sweep.
    Rgb irradianceAt(int polygon, const Vec3& x) const;

    /// Importance from the photo's fixed camera (Smits, Arvo & Salesin 1992), for the
    /// refinement: `seen` holds, per input polygon, the importance it receives directly
    /// (1 where the photo sees it, 0 where it does not). The oracle then weighs each link's
    /// error by the importance of its receiver, so that what the photo shows is refined
    /// first and the surfaces behind the camera cost little. After the first refinement
    /// round the importance takes one bounce of the adjoint equation, through the links:
    ///   I(s) = I_seen(s) + sum_r w_r rho_r I_seen(r) / sum_r w_r,  w_r = F_rs V A_r
    /// over the links r <- s (the power s sends to r), the share of what s sends that a
    /// seen surface reflects, so that a wall behind the camera that lights the seen ones
    /// keeps its links (radiosity/importance.cpp). Every
    /// importance is at least kImportanceFloor and at most 1. Empty (the default): every
    /// receiver counts fully. Call before solve().
    void setCameraImportance(std::vector<double> seen);
    static constexpr double kImportanceFloor = 0.1;
    /// What the photo's camera sees, per input polygon (1 seen, 0 not; relight's item
    /// buffer), for the refinement threshold: epsilon times the power that reaches what the
    /// camera sees, not all the emitted power (seenPowerShare()). A room lit through a
    /// window receives a few percent of the sun and sky's power, the walls' and roof's
    /// outsides the rest: the plain threshold, epsilon times all of it, left the inside
    /// coarse. Empty (the default): all of it. Call before solve().
    void setCameraSeen(std::vector<double> seen);
    /// The share of the emitted power the threshold follows, in [seenPowerFloor, 1]: the
    /// emitters' direct power on the leaves of seen polygons, plus the lamps' emitted power
    /// (their light is not known to land anywhere before their links are refined, by this
    /// very threshold: it counts in full, so rooms lit by lamps keep the plain criterion),
    /// over the emitters' direct power on all leaves plus the lamps'. 1 without a camera.
    double seenPowerShare() const;
    /// The importance of a node's receiving surfaces (1 without camera importance).
    double importanceOf(int node) const;

    /// The active links gathered by `node` (empty when it has none).
    std::span<const Link> linksOf(int node) const;

    /// Reflectance edit of one polygon: updates its elements (links are kept); call
    /// pullReflectance() after a batch of edits (the clusters' means), then solve() or
    /// gatherPushPull(). (Pulling after each edit made 22 k polygons take minutes.)
    void setReflectance(int polygon, const Rgb& rho);
    /// Reflectance edit of one leaf element (per-element reflectance estimated from its
    /// texture, Loscos et al. 2000, §4.4); call pullReflectance() after a batch of them.
    void setElementReflectance(int leaf, const Rgb& rho);
    void pullReflectance() { h_.pullAverages(Hierarchy::kRoot); }

    /// The irradiance every element node receives (element nodes: the sum over the links
    /// of the node and of all its ancestors, a cluster ancestor's through its vector
    /// irradiance; cluster nodes: 0) when each source s of a link sends radiosity
    /// value(s). With `bounded`, a leaf's sum is scaled by its gatherScale, as the solution
    /// is. gatherDown(B of the sources) is what the last sweep gathered. With `uncorrected`,
    /// a link from a light carries its visibility without the real-shadow removal's link
    /// correction (Link::corrected): what the receiver sees of the lamp.
    std::vector<Rgb> gatherDown(const std::function<Rgb(int)>& value, bool bounded,
                                bool uncorrected = false) const;

    /// Light exchanged by `node` with each light (scene order): the sums of F and F V over
    /// the active links it gathers from that light's emitting elements. With the light
    /// links at the leaves (forceLightLinksToLeaves), F V / F is the leaf's visibility of
    /// the light (Loscos et al. 2000, §4.2-4.3).
    struct LightExchange {
        double F = 0, FV = 0;
    };
    std::vector<LightExchange> lightExchange(int node) const;

    /// Texture-based refinement (Loscos et al. 2000, §4.2, Fig. 12): splits leaf element
    /// `leaf` into 4 and moves its links from lights to the children, each with its own
    /// form factor and visibility (the leaf's light links become passive). Links it
    /// gathers from other nodes stay on it: indirect light is gathered higher up and
    /// pushed down. Fills `children` with each child's lightExchange. Returns false (and
    /// changes nothing) for a cluster, a non-leaf, or a leaf at the minimum area.
    bool splitForLights(int leaf, std::vector<std::vector<LightExchange>>* children = nullptr);
    /// Cancels the last splitForLights(leaf): the children (the newest nodes) and their
    /// links go, the leaf's light links come back at their places in the link list (the
    /// list is then the one before the split, unless a read by receiver sorted it in
    /// between). Throws std::logic_error otherwise.
    void unsplit(int leaf);

    /// Link correction of real-shadow removal (Loscos et al. 2000, Eq. (14)-(15)):
    /// multiplies V of the links `node` gathers from lights by c >= 0, so that they carry
    /// C_link V F E (V may then exceed 1). Call gatherPushPull() after a batch.
    void scaleLightLinks(int node, double c);

    const Scene& scene() const { return scene_; }
    const Hierarchy& hierarchy() const { return h_; }
    /// The active links, sorted by receiver.
    const std::vector<Link>& links() const { return links_.byReceiver(); }
    const std::vector<Link>& passiveLinks() const { return passive_; }
    const Visibility& visibility() const { return *vis_; }
    const SolverOptions& options() const { return options_; }
    SolverStats stats() const;
    /// Fewer shaft tests than this in a solve decide nothing about them (shaftTestsPay).
    static constexpr uint64_t kShaftSample = 10000;
    double minArea() const { return minArea_; }
    /// A solve() now would refine no link: its time budget was reached, or
    /// SolverOptions::refineUntil has passed (refineSeconds, which each solve() counts
    /// afresh, does not end it). It would only gather again.
    bool refinementOver() const {
        return timeBudgetReached_ || (options_.refineUntil != Clock::time_point::max() &&
                                      Clock::now() >= options_.refineUntil);
    }

  private:
    /// defer: a cluster's self-interaction too weak to refine now, kept aside
    /// (deferredSelf_) and judged again in the next round, with the radiosities then.
    enum class Decision { accept, drop, splitReceiver, splitSource, defer };
    /// The oracle's decision and the power it weighed (rho B F A, radiosity units x m^2),
    /// kForced for splits the method requires whatever the error.
    struct Verdict {
        Decision decision;
        double value;
    };
    static constexpr double kForced = std::numeric_limits<double>::infinity();
    /// Largest bound on F for which a link with a cluster end is kept: a source within
    /// a cone of half-angle asin(sqrt(0.1)) = 18 degrees, where one direction stands for
    /// all of it to within cos(18) = 0.95.
    static constexpr double kFarField = 0.1;
    /// Fraction of the power threshold above which a near-field cluster link is refined.
    static constexpr double kNearFieldPower = 0.1;
    /// A cluster whose normal cone is narrower than this (radians, 90 degrees) is a surface
    /// for the oracle: none of its faces faces away from another, and a larger element
    /// linked to it is split before it is opened (oracle()).
    static constexpr double kSurfaceCone = 1.5707963267948966;
    /// How many times a surface-like cluster's bounding radius an element's must be for the
    /// element to be split first: a cluster that small is nearly a point seen from the
    /// element, so opening it leaves the link's error (the variation of the form factor over
    /// the element) as it was; of comparable sizes the cluster is opened, as before.
    static constexpr double kElementFirstRatio = 4.0;
    /// Strata per side of the rays that measure a lamp face's `seen` (measureSeen).
    static constexpr int kLampSeenSide = 64;
    /// Smallest face cluster whose polygons take its `seen`, measured once
    /// (measureSeenByPatch): below it, a few large polygons are measured one by one.
    static constexpr int kSeenPatchPolygons = 8;
    /// Largest factor by which the energy bound scales a leaf's gather up.
    static constexpr double kMaxRenormalisation = 2.0;
    /// The energy bound's balance: at most this many column/row alternations...
    static constexpr int kBalanceIterations = 8;
    /// ...stopping once the send scales change by less than this fraction (mean by area).
    static constexpr double kBalanceTolerance = 1e-3;
    /// An inserted object that may cover more than this fraction of a leaf's view has the
    /// leaf's `seen` measured again (remeasureSeenNear).
    static constexpr double kSeenChange = 0.01;
    /// A refinement round that refines at most this fraction of the links ends the rounds.
    static constexpr double kSettled = 1e-3;
    /// Whether a solve's shaft tests so far (`tests` of them, `empty` found empty) paid, by
    /// SolverOptions::shaftPayoff.
    bool shaftTestsPay(uint64_t tests, uint64_t empty) const;
    /// In solve()'s rounds, after a batch of visibility evaluations and after each round:
    /// turns the shaft tests off for the rest of the solve once those it made did not pay
    /// (shaftTestsPay), and says so.
    void stopShaftTestsThatDoNotPay();
    /// The shaft counters (tests, empty) when solve() began its rounds.
    std::array<uint64_t, 2> shaftsBeforeSolve_{};
    /// A new shadow is followed for a light that gives at least this share of a leaf's
    /// unoccluded direct light (as the texture-based refinement's minShare,
    /// relight/pipeline/shadow_refinement.h).
    static constexpr double kShadowMinShare = 0.02;
    Verdict oracle(const Link& link) const;
    /// The factor on the power threshold for links to node r: clamp(B / meanB_, darkFloor,
    /// 1), B for an element the radiosity of the dimmest reflecting leaf below it (dimB_; its
    /// own where smaller), for a cluster its own (max channel); 1 before there is a solution.
    double receiverScale(int r) const;
    /// dimB_ from the leaves' radiosities as they stand (refineAll, before the oracle).
    void measureDimmestLeaves();
    /// The source radiosity the oracle weighs for s: the largest of its lights' scaled
    /// radiosities (lightShareB_, of its nearest ancestor that has one for a node made
    /// since), 0 without them.
    double lightShareB(int s) const;
    /// lightShareB_ from each light's response on the current links
    /// (SolverOptions::perLightOracle).
    void updateLightShares();
    Link makeLink(int r, int s) const;
    /// The visibility of `l` evaluated again, with its receiver's link correction when it
    /// carries one (Link::corrected).
    void visibilityAgain(Link& l) const;
    /// A child of `parent` (passive_[parentIndex]) between r and s; visible without rays
    /// when the parent's shaft was empty.
    Link childLink(const Link& parent, int parentIndex, int r, int s) const;
    /// Refines `seeds` by priority within the budget, appending the accepted links to
    /// links_ (visibility evaluated) and the refined ones to passive_.
    void refineLinks(std::vector<Link> seeds);
    void evaluateVisibility(const std::vector<size_t>& pending);
    size_t memoryUsed(size_t queued) const;
    bool withinBudget(size_t queued) const;
    /// Adds what link l brings to its receiver's H (element) or Hv (cluster).
    void gatherInto(const Link& l);
    /// The same for all the links of the i-th receiver run (the layout's directions: valid layout).
    void gatherRun(size_t i);
    /// Energy bound: sets gatherScale of the leaf elements with id >= firstNode from the
    /// sum G of their links' form factors (see the header).
    /// Also the leaves in `also` (scene leaves an inserted object may change the view of).
    void boundGather(size_t firstNode = 0, bool balance = false,
                     const std::vector<int>* also = nullptr);
    /// Measures `seen` again for the scene's leaves (ids < firstNode) whose view the
    /// object `cluster` may change by more than kSeenChange; returns them (the insertion
    /// record keeps their old measures).
    std::vector<int> remeasureSeenNear(int cluster, size_t firstNode);
    /// The same for an object bounded by the sphere (c, r), its own leaves left out.
    std::vector<int> remeasureSeenNear(const Vec3& c, double r, size_t firstNode, int object);
    /// The snapshot removeLastObject() restores (per node B, Bsent, H, scales; links).
    struct Insertion;
    Insertion snapshot() const;
    /// The row half of the energy bound: gatherScale of the leaves with id >= firstNode
    /// and those in `also`.
    void boundRows(size_t firstNode, const std::vector<Rgb>& Gd, const std::vector<int>* also);
    /// The balance (send_balance.cpp): up to kBalanceIterations of sendScale of every
    /// reflecting leaf (columns), then gatherScale of every leaf (rows); only of the
    /// leaves with id >= firstNode (an inserted object's), the rest held as they are.
    void balanceSends(const std::vector<Rgb>& Gd, size_t firstNode = 0,
                      const std::vector<int>* also = nullptr);
    /// gatherScale of a leaf that sees `seen` (+- seenError) and whose links' form factors
    /// from reflecting sources (weighted by what they send) sum to g, and to the lamps gd;
    /// `group`: the factor its ancestors' leaves moved it by together (groupRowScales).
    static double rowScale(double seen, double seenError, double g, double gd, double group = 1);
    /// Per node, the factor on G that the area means of the leaves below each ancestor
    /// element ask for, each within 2 standard errors of their `seen` (energy_bound.cpp):
    /// g(n) a leaf's G, gd(n) its lamps' form factors.
    std::vector<double> groupRowScales(const std::function<double(int)>& g,
                                       const std::function<double(int)>& gd) const;
    /// Area-weighted mean of value(leaf element) at every node.
    std::vector<double> meanOverLeaves(const std::function<double(const Node&)>& value) const;
    /// Scales the links from each emitting face so that they deliver its area times the
    /// fraction of its hemisphere that sees a surface (solve() and new light links only:
    /// after real-shadow removal has scaled light links on purpose it must not run). Only
    /// the faces from polygon `firstPolygon` on: an inserted light's, leaving the scene's
    /// lamps (and their link corrections) alone.
    void normaliseLamps(int firstPolygon = 0);
    /// Ray casts the `seen` fraction of these elements: first side^2 cosine-distributed rays
    /// (stratified), then more^2 where they disagree. Leaves: 64, then 256 (the energy
    /// bound allows for the error). Lamps' faces: 4096 at once (normaliseLamps scales all of
    /// a lamp's light by it: 256 rays left it +-2.5 %, and the tessellated Cornell box's lamp
    /// read 0.809 against the quads' 0.832).
    void measureSeen(const std::vector<int>& leaves, int side = 8, int more = 16);
    /// The same, but the leaves that are whole polygons of a face cluster of several
    /// (Hierarchy::polygonPatch) take their face cluster's `seen`, measured once for it.
    void measureSeenByPatch(const std::vector<int>& leaves);
    /// solve(): measures what the leaves that are not lamps see, before refining.
    void measureSeenBeforeRefining();
    /// measureSeenByPatch, given up at the refinement's deadline; whether it ended.
    bool measureSeenUntilDeadline(const std::vector<int>& leaves);
    static constexpr size_t kSeenReported = 10000;  ///< leaves from which it is reported
    [[noreturn]] void throwNotConverged(int sweeps, double power, double delta) const;
    /// One refinement pass over the active links; returns how many were refined.
    size_t refineAll();
    void pushLightLinksToLeaves(size_t from = 0);
    /// The links whose shafts `box` cuts get their visibility again; links with an end on
    /// `object`'s polygons are left out. With `revive`, passive links the box now blocks
    /// entirely become active again (an insertion; a removal only opens links).
    void cutLinks(const Bounds3& box, int object, DynamicUpdate& report, bool revive = true);
    /// What an object in `box` changes in the link tree: the active links whose shafts it
    /// cuts, the passive links it blocks entirely (revived in place of their subtrees, whose
    /// active links are marked erased), and the time spent on their visibility.
    struct CutLinks {
        std::vector<int> cut;
        std::vector<Link> revived;
        std::vector<char> erased;  ///< per active link
        double timeVisibility = 0;
    };
    CutLinks findCutLinks(const Bounds3& box, int object, DynamicUpdate& report, bool revive);
    void linkObject(int cluster, int oldRoot, DynamicUpdate& report);
    /// Splits the leaves of report.shadowLeaves that the scene had at the first insertion
    /// where a link from a light is now PARTIAL (SolverOptions::newShadowSplits); counts the
    /// splits kept in report.shadowSplits.
    void refineNewShadows(DynamicUpdate& report);
    /// Whether a shadow boundary crosses leaf element `leaf`: one of its links from a light
    /// that gives at least kShadowMinShare of its unoccluded direct light is PARTIAL.
    bool crossedByShadow(int leaf) const;
    /// The factor normaliseLamps() put on link `l` from a light (1 for another link).
    double lampScale(const Link& l) const;
    /// A child r of link `l` from a light (passive_[parentIndex]), carrying what l carried
    /// beyond its geometry: the lamp's normalisation `scale` and the link correction.
    Link lightChildLink(const Link& l, int parentIndex, int r, double scale) const;
    /// Its visibility (with the receiver's link correction when it carries one).
    void finishLightChildLink(Link& c) const;
    int lightOfNode(int node) const;
    void addLinksFromSource(int node);
    /// Links for the lights that are on and have none (see setLightRadiances); returns
    /// whether any were added.
    bool addMissingLightLinks();
    /// Whether the push-pull layout is that of the links and nodes as they are.
    bool layoutCurrent() const;
    void pushPull(int node, const Rgb& Hdown, const Rgb& HdDown);
    /// What the cluster ancestors of a polygon's root element gathered, by its normal.
    Rgb fromClusterAncestors(int element) const;
    /// The compact layout the gather and push-pull read (gather_push_pull.cpp).
    void buildPushPullLayout();
    /// pushPull from the root: the polygons' element trees in parallel, then the clusters.
    void pushPullAll();
    bool canSplit(int node) const;
    /// The oracle on a cluster's link to itself (oracle(), "self-interaction").
    Verdict selfVerdict(int node) const;
    /// The ambient irradiance before any gather, for `emitted` power (selfVerdict).
    double ambientIrradiance(double emitted) const;
    /// Mean reflectance at most assumed by ambientIrradiance: a room of rho 0.95 has 20
    /// times its first bounce, not an infinite ambient.
    static constexpr double kMaxAmbientReflectance = 0.95;
    void report(const std::string& msg) const;

    Scene scene_;
    SolverOptions options_;
    /// When construction began: set before h_ is built, so that timeBuild counts the face
    /// clusters and the hierarchy (seconds on a 10^5-triangle mesh), not only the BVH.
    Clock::time_point constructed_ = Clock::now();
    Hierarchy h_;
    std::unique_ptr<Visibility> vis_;
    std::unique_ptr<TransferEvaluator> transfer_;
    ActiveLinks links_;          ///< active links, grouped by receiver (active_links.h)
    std::vector<Link> passive_;  ///< refined-away links, kept for dynamic updates
    /// Clusters whose self-interaction solve() left unrefined (Decision::defer), and the
    /// irradiance the first round's oracle assumes before any gather (selfVerdict).
    std::vector<int> deferredSelf_;
    bool deferSelf_ = false;  ///< only solve()'s rounds defer; dynamic updates split
    double ambientIrradiance_ = 0;
    double minArea_ = 0;
    double powerThreshold_ = 0;  ///< epsilon * emitted power * seenPowerShare() (max channel)
    /// Sets powerThreshold_ from the emitted power now (and reports a seen share below 1).
    void setPowerThreshold();
    std::vector<int> emitterLights_;  ///< lights with an emitter
    std::vector<double> Hunit_;       ///< [node * emitterLights + j], leaves only
    /// Hx of every leaf from Hunit_ and the lights' radiances; directPower_.
    void sumDirectIrradiance();
    /// After a dynamic change of the geometry: the emitters' direct light measured again on
    /// every leaf (an object shades the sun and the sky anywhere, not only where it cuts a
    /// link); the leaves where it changed join report.shadowLeaves.
    void refreshEmitterLight(DynamicUpdate& report);
    Rgb directPower_;  ///< sum Hx A over the leaves (radiosity units x m^2)
    /// The faces' emitted power plus directPower_ (max channel): what the oracle and the
    /// convergence test measure against.
    double sourcePower() const;
    /// Camera importance (setCameraImportance): direct, per polygon; the total per polygon
    /// and per cluster node (the largest of its polygons'); whether the bounce was taken.
    std::vector<double> seenImportance_, polygonImportance_;
    std::vector<double> cameraSeen_;  ///< setCameraSeen, per polygon
    std::vector<float> clusterImportance_;
    bool importanceBounced_ = false;
    /// Sets polygonImportance_ and clusterImportance_ from seenImportance_, plus one
    /// bounce through the active links when `bounce`.
    void updateImportance(bool bounce);
    /// Per node: max over lights l of k_l |L_l R_l(node)| (max channel), k_l = (sum over
    /// lights of their reflected power) / (light l's), at most perLightOracle; empty: off.
    std::vector<float> lightShareB_;
    /// Per element node: the radiosity of the dimmest reflecting leaf below it (max channel;
    /// +inf where none reflects, and for clusters), as the last refinement round began;
    /// empty with darkFloor 1.
    std::vector<float> dimB_;
    double meanB_ = 0;  ///< area-weighted mean radiosity of the reflecting leaves (max channel)
    size_t maxLinks_ = 0, maxMemory_ = 0;  ///< the budget in force
    bool budgetReached_ = false;
    bool timeBudgetReached_ = false;
    /// The end of solve()'s time budget (SolverOptions::refineSeconds); the largest time
    /// point outside solve() and without a budget.
    Clock::time_point refineDeadline_ = Clock::time_point::max();
    /// Whether the refinement's time is up, with `queued` links still to be popped and
    /// `pending` accepted links still to have their visibility evaluated (reads the clock
    /// every kClockStride calls); reports progress every kProgressSeconds while refining.
    bool outOfTime(size_t queued, size_t pending);
    static constexpr int kClockStride = 1024;
    /// Seconds a link's visibility takes, measured on batches of at least kLinksTimed
    /// links; before that, 5 microseconds (a 2-core laptop on a 10^5-triangle room).
    double secondsPerLink_ = 5e-6;
    /// Seconds a pop of the refinement's queue takes (the oracle, the heap), measured
    /// between clock readings; before that, 1 microsecond.
    double secondsPerPop_ = 1e-6;
    Clock::time_point lastClock_{};   ///< the last reading in this refineLinks() ({}: none)
    size_t pops_ = 0, lastPops_ = 0;  ///< pops of the queue, all and at lastClock_
    static constexpr size_t kLinksTimed = 10000;
    /// Accepted links whose visibility refineLinks evaluates at once (at least kLinksTimed).
    static constexpr size_t kVisibilityBatch = 65536;
    static constexpr double kProgressSeconds = 10;
    size_t clockCalls_ = 0;
    Clock::time_point lastProgress_{};
    int boundedLeaves_ = 0;
    double maxGather_ = 1;
    bool started_ = false;
    bool changedInRefine_ = false;
    /// refineNewShadows() at work: the scene's frozen leaves may be split.
    bool shadowSplitting_ = false;
    /// The links' generation (ActiveLinks::generation) of the last sweep: when it changed,
    /// the next sweep clears every node's irradiance, not only the receivers'.
    uint64_t sweptGeneration_ = ~uint64_t{0};
    /// What the push-pull reads: per node its parent and (receiving clusters) a slot, per
    /// slot the cluster's frame; the clusters and the polygons' root elements. Rebuilt
    /// when the links are indexed again (their generation) and when the node count changes.
    struct PushPullLayout {
        bool valid = false;
        uint64_t generation = 0;  ///< the links' generation it was built for
        size_t nodes = 0;
        std::vector<int> parent, slot, clusters, roots;
        std::vector<std::array<Vec3, 3>> frame;
        /// Per receiver run i of a cluster: its links' source directions in its frame,
        /// dir[dirStart[i] + k] for its k-th link (-1 for an element receiver).
        std::vector<int> dirStart;
        std::vector<Vec3> dir;
    };
    PushPullLayout layout_;
    struct SplitRecord {
        int leaf = -1;
        std::vector<Link> removed;  ///< the leaf's light links, moved to passive_
        std::vector<size_t> at;     ///< their indices in links_ before the split
    } lastSplit_;
    SolverStats timing_;
    /// What removeLastObject() restores, one per inserted object (a stack).
    struct Insertion {
        std::vector<Link> links;  ///< links_ before (sorted by receiver)
        size_t passive = 0, polygons = 0, objects = 0, lights = 0;
        std::vector<Rgb> B, Bsent, H;               ///< per node before
        std::vector<std::array<double, 2>> scales;  ///< per node before: gather, send
        /// Leaves whose `seen` the insertion measured again: (leaf, seen, seenError) before.
        std::vector<std::tuple<int, double, double>> reseen;
        std::vector<DirectionalIrradiance> Hv;  ///< per cluster slot before
        std::vector<Rgb> Hd;
        std::vector<int> retired;       ///< passive links retired by this insertion
        std::vector<int> shadowLeaves;  ///< DynamicUpdate::shadowLeaves of the insertion
        std::string name;
        bool light = false;
        Rgb radiance;
        int visGroup = -1;
        size_t frozenNodes = 0;
        /// A real object taken out (removeRealObject): its index, its polygons, and every
        /// node's reflectance before; -1 for an insertion.
        int removed = -1;
        std::vector<int> hidden;
        std::vector<Rgb> rho;
    };
    std::vector<Insertion> inserted_;
    size_t frozenNodes_ = 0;  ///< leaves below this id are not split (0: no limit)
};

}  // namespace radiosity
