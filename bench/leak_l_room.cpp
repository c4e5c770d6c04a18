// Light round a corner: an L-shaped enclosure lit in one arm only, the hierarchical
// solution against the full-matrix reference (radiosity/reference_solver.h), per epsilon.
//
//   ./build/bench/leak_l_room [epsilons...]      (default 1e-3 1e-4 1e-5)
//
// The enclosure is 1 m high: arm A along x ([0,4] x [0,1]), arm B along y ([0,1] x [1,4]);
// rho 0.6, one 0.4 m lamp under the ceiling at the far end of arm A. Arm B is lit only by
// light that turned the corner. Printed: the ratio of the mean radiosity over arm B's far
// half (y > 2.5) to the reference's, the same for arm A's far half (x > 2), links,
// leaves and the share of the lamp's power absorbed (the enclosure is closed).
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "radiosity/reference_solver.h"
#include "radiosity/solver.h"
#include "tests/support/l_room.h"

using namespace radiosity;
using radiosity::test::lRoom;

int main(int argc, char** argv) {
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\n");
    std::vector<double> eps;
    for (int i = 1; i < argc; ++i) eps.push_back(std::atof(argv[i]));
    if (eps.empty()) eps = {1e-3, 1e-4, 1e-5};
    const Scene s = lRoom();
    ReferenceOptions ro;
    ro.maxArea = 0.04;
    ReferenceSolver ref(s, ro);
    ref.solve();
    std::printf("reference: %zu elements of at most 0.04 m^2\n", ref.leaves().size());
    std::printf("%8s %14s %14s %9s %8s %9s\n", "epsilon", "arm B far", "arm A far", "links",
                "leaves", "absorbed");
    for (double e : eps) {
        SolverOptions o;
        o.epsilon = e;
        HierarchicalSolver solver(s, o);
        solver.solve();
        double hrB = 0, refB = 0, hrA = 0, refA = 0;
        const Hierarchy& h = ref.hierarchy();
        for (int leaf : ref.leaves()) {
            const Node& n = h.nodes[leaf];
            if (n.emitting) continue;
            const double b = solver.radiosityAt(n.polygon, n.centre).r;
            if (n.centre.y >= 2.5) {
                hrB += b * n.area;
                refB += n.B.r * n.area;
            }
            if (n.centre.x >= 2.0) {
                hrA += b * n.area;
                refA += n.B.r * n.area;
            }
        }
        const SolverStats st = solver.stats();
        std::printf("%8.0e %13.3fx %13.3fx %9d %8d %8.1f%%\n", e, hrB / refB, hrA / refA, st.links,
                    st.leaves, 100 * st.absorbedPower.r / st.emittedPower.r);
    }
    return 0;
}
