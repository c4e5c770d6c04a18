// Energy in a closed room: what the room absorbs against what its lamp emits, for the room
// of tests/support/cut_room.h (4 x 3 x 2.5 m, its faces cut into triangles, one lamp flush
// in the ceiling, no surface showing its back), per cut, reflectance and epsilon.
//
//   ./build/bench/closed_room [epsilons...]      (default 1e-3 1e-4)
//
// Printed: absorbed / emitted (red channel; the room is grey), the links, and the range of
// the energy bound's per-leaf gather scale (radiosity/solver.h: each leaf's links scaled
// to sum to what it sees). In a closed room every unit of emitted power is absorbed
// somewhere; a ratio below 1 is light the links lose, above 1 light they make.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "radiosity/solver.h"
#include "tests/support/cut_room.h"

using namespace radiosity;

int main(int argc, char** argv) {
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\n");
    std::vector<double> eps;
    for (int i = 1; i < argc; ++i) eps.push_back(std::atof(argv[i]));
    if (eps.empty()) eps = {1e-3, 1e-4};
    std::printf("%8s %4s %5s %10s %9s %15s %15s\n", "epsilon", "cut", "rho", "absorbed", "links",
                "gather scale", "send scale");
    for (double e : eps)
        for (double rho : {0.7, 0.95})
            for (int cut : {1, 2, 4, 8}) {
                SolverOptions o;
                o.epsilon = e;
                HierarchicalSolver solver(test::cutRoom(cut, rho, /*box=*/false), o);
                solver.solve();
                const SolverStats st = solver.stats();
                double lo = 1e300, hi = 0, slo = 1e300, shi = 0;
                for (const Node& n : solver.hierarchy().nodes) {
                    if (n.isCluster() || !n.isLeaf()) continue;
                    lo = std::min(lo, n.gatherScale);
                    hi = std::max(hi, n.gatherScale);
                    slo = std::min(slo, n.sendScale);
                    shi = std::max(shi, n.sendScale);
                }
                std::printf("%8.0e %4d %5.2f %9.2f%% %9d %7.3f..%5.3f %7.3f..%5.3f\n", e, cut, rho,
                            100 * st.absorbedPower.r / st.emittedPower.r, st.links, lo, hi, slo,
                            shi);
                std::fflush(stdout);
            }
    return 0;
}
