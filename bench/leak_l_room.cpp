// Light round a corner: an L-shaped enclosure lit in one arm only, the hierarchical
// solution against the full-matrix reference (radiosity/reference_solver.h), per epsilon.
//
//   ./build/bench/leak_l_room [--cut N] [--arm A|B] [--no-balance] [--rays MIN MAX]
//                             [--dark-floor F] [--scales] [epsilons...]
//                             (default 1e-3 1e-4 1e-5)
//   ./build/bench/leak_l_room --reference-areas 0.02 0.01
//
// --reference-areas checks the yardstick instead: the reference solved again with
// elements of at most each given area (m^2), its arm B far half against the 0.04 m^2
// one's (1: the reference is converged, so the ratios above measure the solver).
//
// --cut N cuts the faces into N x N quads (all of them, or only those of arm A or B with
// --arm): the same room as many small polygons, which the solver clusters, rather than
// 10 large ones, which it subdivides. --no-balance leaves out the balance of what leaves
// send (radiosity/solver.h). --rays sets the links' visibility rays: MIN first, MAX in all
// in penumbra (TransferOptions). --dark-floor sets SolverOptions::darkFloor (relight's
// preparation uses 0.1, RelightOptions; the solver's own default 1 is the plain criterion).
// --scales prints, per region (arm A's far and near halves, the corner square, arm B's near
// and far parts), the area means of the energy bound's gather and send scales and of what
// the leaves see, what they hand to the lamp's face through their links against what they
// gather from it (equal by reciprocity), and each region's ratio to the reference.
//
// The enclosure is 1 m high: arm A along x ([0,4] x [0,1]), arm B along y ([0,1] x [1,4]);
// rho 0.6, one 0.4 m lamp under the ceiling at the far end of arm A. Arm B is lit only by
// light that turned the corner. Printed: the ratio of the mean radiosity over arm B's far
// half (y > 2.5) to the reference's, the same for arm A's far half (x > 2), links,
// leaves and the share of the lamp's power absorbed (the enclosure is closed).
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "radiosity/reference_solver.h"
#include "radiosity/solver.h"
#include "tests/support/l_room.h"

using namespace radiosity;
using radiosity::test::lRoom;

namespace {

/// The room with its faces (of arm A or B only, or all with arm 0) cut into n x n quads;
/// the lamp as it is.
Scene cutFaces(const Scene& room, int n, char arm) {
    if (n <= 1) return room;
    Scene s = room;
    s.polygons.clear();
    for (Light& l : s.lights) l.polygons.clear();
    for (const Polygon& p : room.polygons) {
        const bool inB = p.centroid().y > 1.0;  // the x = 0 wall (y 0..4) counts as arm B
        if (p.light >= 0 || (arm == 'A' && inB) || (arm == 'B' && !inB)) {
            if (p.light >= 0) s.lights[p.light].polygons.push_back(int(s.polygons.size()));
            s.polygons.push_back(p);
            continue;
        }
        auto at = [&](double u, double v) {
            return (1 - u) * (1 - v) * p.v[0] + u * (1 - v) * p.v[1] + u * v * p.v[2] +
                   (1 - u) * v * p.v[3];
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const double u0 = double(i) / n, u1 = double(i + 1) / n;
                const double v0 = double(j) / n, v1 = double(j + 1) / n;
                s.polygons.push_back(
                    makePolygon({at(u0, v0), at(u1, v0), at(u1, v1), at(u0, v1)}, p.object, p.rho));
            }
    }
    return s;
}

/// The ratio of solution B's area-weighted mean over the reference's elements in a
/// region (inside(centre)) to the reference's own: B is read at each element's centre.
template <class Solution, class Inside>
double regionRatio(const ReferenceSolver& ref, const Solution& B, const Inside& inside) {
    double num = 0, den = 0;
    for (int leaf : ref.leaves()) {
        const Node& n = ref.hierarchy().nodes[leaf];
        if (n.emitting || !inside(n.centre)) continue;
        num += B(n.polygon, n.centre) * n.area;
        den += n.B.r * n.area;
    }
    return den > 0 ? num / den : 0.0;  // guard: an empty region
}

bool armBFar(const Vec3& c) {
    return c.y >= 2.5;
}
bool armAFar(const Vec3& c) {
    return c.x >= 2.0;
}

/// The regions of --scales: arm B (y > 1, its wall at x = 1 included) near (y < 2.5) and
/// far; arm A (x > 1, its wall at y = 1 included) near (x < 2) and far; the corner square.
constexpr int kRegions = 5;
const char* const kRegionNames[kRegions] = {"arm A far", "arm A near", "corner", "arm B near",
                                            "arm B far"};
int regionOf(const Vec3& c) {
    constexpr double kSide = 1 + 1e-9;  // the arms' inner walls lie on x = 1 and y = 1
    if (c.y > kSide) return c.y < 2.5 ? 3 : 4;
    if (c.x > kSide) return c.x < 2 ? 1 : 0;
    return 2;
}

/// --scales: the energy bound's scales per region, and the lamp's exchange both ways.
void printScales(const HierarchicalSolver& solver, const ReferenceSolver& ref) {
    const auto& nodes = solver.hierarchy().nodes;
    // Per node, what its links from reflecting sources hand to the lamp's face (F V A_r)
    // and what its links from the lamp bring it (F V); summed down to the leaves (parents
    // come before their children in the node array), a leaf's per unit area.
    std::vector<double> toLamp(nodes.size(), 0.0), fromLamp(nodes.size(), 0.0);
    for (const Link& l : solver.links()) {
        const Node& R = nodes[l.receiver];
        const double FV = l.F * static_cast<double>(l.V);
        if (R.emitting && !R.isCluster() && reflects(nodes[l.source]))
            toLamp[l.source] += FV * R.area;
        if (!reflects(nodes[l.source])) fromLamp[l.receiver] += FV;
    }
    double A[kRegions] = {}, gather[kRegions] = {}, send[kRegions] = {}, seen[kRegions] = {};
    double to[kRegions] = {}, from[kRegions] = {};
    for (size_t n = 0; n < nodes.size(); ++n) {
        const Node& e = nodes[n];
        toLamp[n] = (e.area > 0 ? toLamp[n] / e.area : 0.0) +  // guard: a zero-area node
                    (e.parent >= 0 ? toLamp[static_cast<size_t>(e.parent)] : 0.0);
        fromLamp[n] += e.parent >= 0 ? fromLamp[static_cast<size_t>(e.parent)] : 0.0;
        if (e.isCluster() || !e.isLeaf() || e.emitting) continue;
        const int k = regionOf(e.centre);
        A[k] += e.area;
        gather[k] += e.area * e.gatherScale;
        send[k] += e.area * e.sendScale;
        seen[k] += e.area * e.seen;
        to[k] += e.area * toLamp[n];
        from[k] += e.area * fromLamp[n];
    }
    // The exchange between regions through the links from reflecting sources, per unit
    // radiosity: T[a][b] = sum F V A_r over the receiver's leaves in a, times the share of
    // the source's area in b (a cluster receiver's light taken by area, as an estimate).
    // Reciprocity: T[a][b] = T[b][a].
    std::vector<std::array<double, kRegions>> areaIn(nodes.size());
    for (size_t n = nodes.size(); n-- > 0;) {
        const Node& e = nodes[n];
        if (e.isLeaf() && !e.isCluster() && !e.emitting)
            areaIn[n][static_cast<size_t>(regionOf(e.centre))] += e.area;
        if (e.parent >= 0)
            for (size_t k = 0; k < kRegions; ++k)
                areaIn[static_cast<size_t>(e.parent)][k] += areaIn[n][k];
    }
    double T[kRegions][kRegions] = {};
    for (const Link& l : solver.links()) {
        const Node& S = nodes[l.source];
        if (!reflects(S) || !(S.area > 0)) continue;
        const double FV = l.F * static_cast<double>(l.V);
        for (int a = 0; a < kRegions; ++a)
            for (int b = 0; b < kRegions; ++b)
                T[a][b] += FV * areaIn[static_cast<size_t>(l.receiver)][static_cast<size_t>(a)] *
                           areaIn[static_cast<size_t>(l.source)][static_cast<size_t>(b)] / S.area;
    }
    std::printf("  reciprocity, T[a][b] / T[b][a] (a: the row's region, b: the column's):\n");
    for (int a = 0; a < kRegions; ++a) {
        std::printf("  %-10s", kRegionNames[a]);
        for (int b = 0; b < kRegions; ++b)
            std::printf(" %7.3f", T[b][a] > 0 ? T[a][b] / T[b][a] : 0.0);
        double row = 0, column = 0, area = 0;
        for (int b = 0; b < kRegions; ++b) {
            row += T[a][b];
            column += T[b][a];
            area += areaIn[0][static_cast<size_t>(a)];
        }
        area /= kRegions;
        // Per unit area: what the region gathers from reflecting sources and hands to
        // reflecting receivers, per unit radiosity (by reciprocity both are what it sees
        // of the reflecting surfaces).
        std::printf("   gathers %.3f, hands out %.3f\n", area > 0 ? row / area : 0.0,
                    area > 0 ? column / area : 0.0);
    }
    const auto B = [&](int p, const Vec3& x) { return solver.radiosityAt(p, x).r; };
    for (int k = 0; k < kRegions; ++k) {
        if (!(A[k] > 0)) continue;  // guard: an empty region
        const double ratio = regionRatio(ref, B, [k](const Vec3& c) { return regionOf(c) == k; });
        std::printf(
            "  %-10s gather scale %.3f  send scale %.3f  seen %.3f  to the lamp %.4f"
            "  from it %.4f  %.3fx\n",
            kRegionNames[k], gather[k] / A[k], send[k] / A[k], seen[k] / A[k], to[k] / A[k],
            from[k] / A[k], ratio);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\n");
    std::vector<double> eps;
    int cut = 1;
    char arm = 0;
    bool balance = true, referenceAreas = false, scales = false;
    double darkFloor = SolverOptions{}.darkFloor;
    int minRays = TransferOptions{}.minRays, maxRays = TransferOptions{}.maxRays;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--reference-areas")
            referenceAreas = true;
        else if (a == "--cut" && i + 1 < argc)
            cut = std::max(1, std::atoi(argv[++i]));
        else if (a == "--arm" && i + 1 < argc)
            arm = argv[++i][0];
        else if (a == "--dark-floor" && i + 1 < argc)
            darkFloor = std::atof(argv[++i]);
        else if (a == "--no-balance")
            balance = false;
        else if (a == "--scales")
            scales = true;
        else if (a == "--rays" && i + 2 < argc) {
            minRays = std::atoi(argv[++i]);
            maxRays = std::atoi(argv[++i]);
        } else
            eps.push_back(std::atof(argv[i]));
    }
    if (eps.empty())
        eps = referenceAreas ? std::vector<double>{0.02, 0.01}
                             : std::vector<double>{1e-3, 1e-4, 1e-5};
    const Scene s = cutFaces(lRoom(), cut, arm);
    ReferenceOptions ro;
    ro.maxArea = 0.04;
    ReferenceSolver ref(s, ro);
    ref.solve();
    std::printf("reference: %zu elements of at most 0.04 m^2\n", ref.leaves().size());
    if (referenceAreas) {
        // Each finer reference read at the 0.04 m^2 reference's element centres, weighted
        // by their areas: the same mean as below.
        for (double area : eps) {
            if (!(area > 0)) {
                std::fprintf(stderr, "leak_l_room: --reference-areas needs areas > 0 m^2, got %g\n",
                             area);
                return 2;
            }
            ReferenceOptions fine;
            fine.maxArea = area;
            ReferenceSolver other(s, fine);
            other.solve();
            const double ratio = regionRatio(
                ref, [&](int p, const Vec3& x) { return other.radiosityAt(p, x).r; }, armBFar);
            std::printf("reference at %g m^2 (%zu elements): arm B far %.4fx the 0.04 m^2 one\n",
                        area, other.leaves().size(), ratio);
        }
        return 0;
    }
    std::printf("%8s %14s %14s %9s %8s %9s\n", "epsilon", "arm B far", "arm A far", "links",
                "leaves", "absorbed");
    for (double e : eps) {
        SolverOptions o;
        o.epsilon = e;
        o.balanceSends = balance;
        o.darkFloor = darkFloor;
        o.transfer.minRays = minRays;
        o.transfer.maxRays = maxRays;
        HierarchicalSolver solver(s, o);
        solver.solve();
        const auto hr = [&](int p, const Vec3& x) { return solver.radiosityAt(p, x).r; };
        const double ratioB = regionRatio(ref, hr, armBFar), ratioA = regionRatio(ref, hr, armAFar);
        const SolverStats st = solver.stats();
        std::printf("%8.0e %13.3fx %13.3fx %9d %8d %8.1f%%\n", e, ratioB, ratioA, st.links,
                    st.leaves, 100 * st.absorbedPower.r / st.emittedPower.r);
        if (scales) printScales(solver, ref);
    }
    return 0;
}
