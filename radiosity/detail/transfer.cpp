#include "radiosity/detail/transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "radiosity/detail/form_factor.h"
#include "radiosity/detail/rng.h"
#include "radiosity/detail/shaft.h"

namespace radiosity {

namespace {

constexpr double kPi = std::numbers::pi;

/// Signed distance of the farthest point of a node in front of a plane (n, p0): > 0 when
/// some part of the node lies strictly in front.
double maxInFront(const Node& node, const Vec3& n, const Vec3& p0) {
    if (!node.isCluster()) {
        double m = -1e300;
        for (int i = 0; i < node.vertexCount; ++i) m = std::max(m, glm::dot(node.v[i] - p0, n));
        return m;
    }
    // Box corner farthest along n.
    const Vec3 far{n.x >= 0 ? node.bounds.hi.x : node.bounds.lo.x,
                   n.y >= 0 ? node.bounds.hi.y : node.bounds.lo.y,
                   n.z >= 0 ? node.bounds.hi.z : node.bounds.lo.z};
    return glm::dot(far - p0, n);
}

}  // namespace

Vec3 linkDirection(const Node& R, const Node& S) {
    const Vec3 d = S.centre - R.centre;
    const double len = glm::length(d);
    return len > 0 ? d / len : Vec3{0, 0, 0};
}

double pointToNode(const Hierarchy& h, const Vec3& x, const Vec3& n, const Node& S) {
    const Vec3 d = S.centre - x;
    const double d2 = glm::dot(d, d);
    if (!(d2 > 0)) return 0.0;  // x at the source's centre: no direction
    const Vec3 w = d / std::sqrt(d2);
    return discFormFactor(glm::dot(n, w), 1.0, d2, h.projectedArea(S, -w));
}

bool TransferEvaluator::facing(int r, int s) const {
    const Node& R = h_.nodes[r];
    const Node& S = h_.nodes[s];
    // Tolerance: 1e-9 of the larger node radius, so that coplanar elements (same plane,
    // numerically) count as not facing.
    const double tol = 1e-9 * std::max(R.radius, S.radius) + 1e-12;
    if (!R.isCluster() && !(maxInFront(S, R.normal, R.v[0]) > tol)) return false;
    if (!S.isCluster() && !(maxInFront(R, S.normal, S.v[0]) > tol)) return false;
    return true;
}

double TransferEvaluator::formFactor(int r, int s) const {
    counters.formFactors.fetch_add(1, std::memory_order_relaxed);
    const Node& R = h_.nodes[r];
    const Node& S = h_.nodes[s];
    if (!R.isCluster() && !S.isCluster()) {
        return polygonToPolygon(R.v.data(), R.vertexCount, R.normal, S.v.data(), S.vertexCount,
                                S.normal, options_.quadratureOrder);
    }
    const Vec3 d = S.centre - R.centre;
    const double d2 = glm::dot(d, d);
    // Coincident centres (two clusters about one point): no direction to weigh a
    // receiver's cosine by; such a link is always refined (bound() is 1), and meanwhile
    // carries nothing.
    if (!(d2 > 0)) return 0.0;
    const Vec3 w = d / std::sqrt(d2);
    const double As = h_.projectedArea(S, -w);
    // The receiver's cosine for an element; for a cluster the gather applies each of its
    // surfaces' own (vector irradiance).
    const double cosR = R.isCluster() ? 1.0 : glm::dot(R.normal, w);
    return std::min(discFormFactor(cosR, 1.0, d2, As), coneBound(r, s));
}

double TransferEvaluator::coneBound(int r, int s) const {
    const Node& R = h_.nodes[r];
    const Node& S = h_.nodes[s];
    // The two cones about their bisector: every normal within half the angle between the
    // axes plus the wider cone's angle.
    const double between =
        std::acos(std::clamp(glm::dot(h_.coneAxis(R), h_.coneAxis(S)), -1.0, 1.0));
    const double alpha = 0.5 * between + std::max(h_.coneAngle(R), h_.coneAngle(S));
    if (!(alpha < kPi / 2)) return 1.0;  // 8 delta^2 >= 1 long before: no bound
    const double delta = 2 * std::sin(0.5 * alpha);
    return std::min(1.0, 8 * delta * delta);
}

double TransferEvaluator::bound(int r, int s, double F) const {
    const Node& R = h_.nodes[r];
    const Node& S = h_.nodes[s];
    if (!R.isCluster() && !S.isCluster()) return F;
    const double cone = coneBound(r, s);
    const Vec3 d = S.centre - R.centre;
    const double dist = glm::length(d);
    const double dMin = dist - R.radius - S.radius;
    if (!(dMin > 0)) return cone;
    const double As = h_.projectedArea(S, -d / dist);
    return std::min({1.0, cone, As / (kPi * dMin * dMin)});
}

double TransferEvaluator::receiverArea(int r, int s) const {
    const Node& R = h_.nodes[r];
    if (!R.isCluster()) return R.area;
    const Vec3 d = h_.nodes[s].centre - R.centre;
    const double dist = glm::length(d);
    // Coincident centres: no direction; the whole area is the safe (larger) estimate.
    if (!(dist > 0)) return R.area;
    return h_.projectedArea(R, d / dist);
}

bool TransferEvaluator::shaftQuery(const Shaft& shaft, int node, int skipA, int skipB,
                                   const Bounds3& box) const {
    const Node& n = h_.nodes[node];
    // A box that only touches the shaft's outer box (a wall in the plane of a face of the
    // union box) cannot block an open segment inside it: treat touching as outside.
    const double tol = 1e-9 * (1.0 + glm::length(box.diagonal()));
    for (int a = 0; a < 3; ++a) {
        if (n.bounds.hi[a] <= box.lo[a] + tol || n.bounds.lo[a] >= box.hi[a] - tol) return false;
    }
    if (!shaft.mayIntersect(n.bounds)) return false;
    if (!n.isCluster()) return n.polygon != skipA && n.polygon != skipB;
    for (int k = 0; k < n.childCount; ++k) {
        if (shaftQuery(shaft, n.firstChild + k, skipA, skipB, box)) return true;
    }
    return false;
}

bool TransferEvaluator::shaftIsEmpty(int r, int s) const {
    counters.shaftTests.fetch_add(1, std::memory_order_relaxed);
    const Node& R = h_.nodes[r];
    const Node& S = h_.nodes[s];
    const Shaft shaft(R.bounds, S.bounds);
    // The polygons a link's ends lie on cannot block it (planar, one-sided); polygons
    // inside an end cluster can, so only element ends are skipped.
    const int skipA = R.isCluster() ? -1 : R.polygon;
    const int skipB = S.isCluster() ? -1 : S.polygon;
    return !shaftQuery(shaft, Hierarchy::kRoot, skipA, skipB, shaft.bounds());
}

void TransferEvaluator::visibility(Link& link, bool thorough, bool narrow) const {
    const int r = link.receiver, s = link.source;
    if (options_.useShafts && shaftTests_ && shaftIsEmpty(r, s)) {
        counters.shaftEmpty.fetch_add(1, std::memory_order_relaxed);
        setShaftEmpty(link);
        return;
    }
    link.shaftEmpty = false;
    const int minRays = std::clamp(options_.minRays, 1, 256);
    const int maxRays = std::clamp(options_.maxRays, minRays, 256);
    Rng rng(0x5EEDull ^ (static_cast<uint64_t>(r) << 32) ^ static_cast<uint64_t>(s) * 0x9E37ull);
    Vec3 from[256], to[256];
    // One stratified set of maxRays pairs: a jittered k x k grid on each end (k^2 >= n),
    // strata visited in independent random orders on the two ends, so any prefix of the
    // set is a uniform sample of both ends: the first minRays rays decide, and in
    // penumbra the rest of the set follows.
    const int k = strataSide(maxRays);
    int permR[256], permS[256], orderS[256];
    shuffledStrata(rng, k, permR);
    shuffledStrata(rng, k, permS);
    // Mutually facing pairs, compacted to the front in draw order. They are drawn only as
    // far as needed: the first minRays of them decide, and the rest of the set is drawn
    // only for a link in penumbra (or `thorough`). Rays use no random numbers, so the
    // pairs are those of drawing the whole set first. (Drawing all maxRays pairs for every
    // link, when most need minRays, was a fifth of a 200 k-triangle room's preparation:
    // each draw in a large cluster reads a random polygon.)
    int m = 0, next = 0;
    const auto draw = [&](int want) {
        for (; next < maxRays && m < want; ++next) {
            const int a = permR[next], b = permS[next];
            // Only mutually facing point pairs carry light between one-sided surfaces; a
            // ray from the back of a block's face would run through the block and count as
            // blocked, biasing V low. Redraw within the strata up to 8 times to find one;
            // a pair never found is left out of the estimate rather than counted blocked.
            for (int attempt = 0; attempt < 8; ++attempt) {
                const double u0 = ((a % k) + rng.uniform()) / k, v0 = ((a / k) + rng.uniform()) / k;
                const double u1 = ((b % k) + rng.uniform()) / k, v1 = ((b / k) + rng.uniform()) / k;
                Vec3 n0, n1;
                from[m] = h_.samplePoint(r, u0, v0, rng.uniform(), &n0);
                to[m] = h_.samplePoint(s, u1, v1, rng.uniform(), &n1, &orderS[m]);
                const Vec3 d = to[m] - from[m];
                if (glm::dot(n0, d) > 0 && glm::dot(n1, d) < 0) {
                    ++m;
                    break;
                }
            }
        }
    };
    draw(thorough ? maxRays : minRays);  // m < minRays only when every stratum was tried
    if (m == 0) {
        // No part of the two faces the other: nothing passes, and no more rays would say
        // otherwise.
        link.rays = static_cast<uint8_t>(maxRays);
        link.V = 0;
        link.type = VisibilityType::invisible;
        return;
    }
    // Rays between two elements ignore hits on the elements' own polygons (grazing
    // rays near a shared edge would otherwise count as blocked).
    const int polyR = h_.nodes[r].isCluster() ? -1 : h_.nodes[r].polygon;
    const int polyS = h_.nodes[s].isCluster() ? -1 : h_.nodes[s].polygon;
    const int first = m;
    int visible = vis_.visibleBatch(from, to, first, nullptr, polyR, polyS);
    int cast = first;
    if (visible != 0 && visible != first) {  // penumbra: the rest of the set
        draw(maxRays);
        if (m > first) {
            visible +=
                vis_.visibleBatch(from + first, to + first, m - first, nullptr, polyR, polyS);
            cast = m;
        }
    }
    counters.rays.fetch_add(static_cast<uint64_t>(cast), std::memory_order_relaxed);
    link.rays = static_cast<uint8_t>(std::min(cast, 255));
    link.V = static_cast<float>(visible) / static_cast<float>(cast);
    link.type = visible == 0      ? VisibilityType::invisible
                : visible == cast ? VisibilityType::visible
                                  : VisibilityType::partial;
    // Only VISIBLE links are narrowed: a PARTIAL one's free rays are often a few, and the
    // node that holds them stands for the whole visible part by a sample of one to three
    // points (tried: the stair hall's lamp-off edits went 1.5-2.5 times worse).
    if (narrow && link.type == VisibilityType::visible && h_.nodes[s].isCluster() &&
        !h_.nodes[s].emitting) {
        int lo = std::numeric_limits<int>::max(), hi = -1;
        for (int i = 0; i < cast; ++i) lo = std::min(lo, orderS[i]), hi = std::max(hi, orderS[i]);
        narrowSource(link, lo, hi);
    }
}

bool TransferEvaluator::turnedAway(int r, int c) const {
    const Node& R = h_.nodes[r];
    const Node& C = h_.nodes[c];
    // Every normal n of c lies within t of its cone's axis a; every direction d from a point
    // of c to one of R lies in the box R.bounds - C.bounds. max over n of n.d is convex in d,
    // so its largest value over the box is at a corner; at a corner it is at most 0 when
    // the angle between a and d is at least t + 90 degrees: a.d / |d| <= -sin t.
    const double t = h_.coneAngle(C);
    if (!(t < kPi / 2)) return false;
    const double sinT = std::sin(t);
    const Vec3& axis = h_.coneAxis(C);
    for (int k = 0; k < 8; ++k) {
        const Vec3 d{((k & 1) ? R.bounds.hi.x - C.bounds.lo.x : R.bounds.lo.x - C.bounds.hi.x),
                     ((k & 2) ? R.bounds.hi.y - C.bounds.lo.y : R.bounds.lo.y - C.bounds.hi.y),
                     ((k & 4) ? R.bounds.hi.z - C.bounds.lo.z : R.bounds.lo.z - C.bounds.hi.z)};
        const double len = glm::length(d);
        if (!(len > 0) || glm::dot(axis, d) / len > -sinT) return false;
    }
    return true;
}

void TransferEvaluator::narrowSource(Link& link, int lo, int hi) const {
    if (hi < lo) return;
    const int s = link.source;
    // F V is the transfer from the part of the source that faces the receiver; with one
    // radiosity for the whole source it carries the mean of all of it, the turned-away
    // parts' too: a lamp shade's bright inside would light the room through its dark
    // outside. The rays (cast between mutually facing points only, all free) ended in
    // polygonOrder[lo, hi]: the link gathers from the narrowest node that holds them, with
    // the same F V (unchanged when the radiosity is uniform). The node is widened again
    // towards s while V would exceed 1: a node smaller than what the receiver sees of s
    // (the rays' ends are a sample of it) would lose light.
    const double FV = link.F * static_cast<double>(link.V);
    int d = h_.narrowestCovering(s, lo, hi);
    // What is left out must send nothing to the receiver: a sibling on the way up from the
    // node that is not provably turned away from it (a few rays can miss a part that faces
    // it) keeps its parent in. (Narrowed to the rays' ends alone, a closed room refined to
    // epsilon 1e-5 absorbed 97.9 % of its light.)
    for (int a = d; a != s;) {
        const int up = h_.nodes[a].parent;
        const Node& A = h_.nodes[up];
        for (int k = 0; k < A.childCount; ++k) {
            const int c = A.firstChild + k;
            if (c != a && !turnedAway(link.receiver, c)) d = up;
        }
        a = up;
    }
    double Fd = 0;
    while (d != s) {
        Fd = formFactor(link.receiver, d);
        if (Fd >= FV && Fd > 0) break;
        d = h_.nodes[d].parent;
    }
    if (d == s) return;
    link.source = d;
    link.F = Fd;
    link.V = static_cast<float>(std::min(1.0, FV / Fd));
}

}  // namespace radiosity
