// A lamp in a closed shade whose walls are thin sheets (two back-to-back faces on the same
// corners, as the staircase's lamp shade and an imported model's thin parts come): no light
// of that lamp may reach anything outside the shade, however coarse the links. This measures
// how much does, and through which links: those whose source is a cluster holding the
// shade's inner faces (a cluster sends the area mean of its surfaces' radiosity the same
// way in every direction, Sillion's isotropic cluster, so the bright inner faces' light
// leaves through the outer ones), or an element.
//
// The shaded lamp is the weak one: the room's ceiling lamp gives 18 times its radiance x
// area (1.78 m^2 at 10 against 0.01 m^2 at 100), as the stair hall's ceiling lamp gives 21
// times its shaded table lamp's. Each case runs with the BF criterion on the total light and
// with the per-light oracle (SolverOptions::perLightOracle, issue 30 "light round corners"),
// and with the links' cluster sources narrowed to what their rays reached
// (SolverOptions::narrowClusterSources, off by default) and, for the first ones, without.
//
//   ./build/bench/shaded_lamp [PER_LIGHT_GAIN]     (default 100)
// prints, with no budget, a budget of links, and none at all (the coarsest links), the lamp's
// reflected radiosity inside and outside the shade (area means per unit radiance), the
// light the links out of the shade carry, and the largest indirect irradiance a ray gather
// finds on the shade's outer faces. All of the outside figures should be 0.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "radiosity/final_gather.h"
#include "radiosity/light_response.h"
#include "radiosity/solver.h"
#include "tests/support/shaded_lamp_room.h"

using namespace radiosity;
using radiosity::test::shadedLampRoom;

int main(int argc, char** argv) {
    const double gain = argc > 1 ? std::atof(argv[1]) : 100.0;
    std::printf("command: ./build/bench/shaded_lamp %g\n", gain);
    const Scene scene = shadedLampRoom(8);
    struct Case {
        double seconds;
        size_t maxLinks;
        double perLight;
        bool narrow = true;
    };
    for (const Case c : {Case{0, 0, 0, false}, Case{0, 0, 0}, Case{0, 0, gain, false},
                         Case{0, 0, gain}, Case{0, 30000, 0, false}, Case{0, 30000, 0},
                         Case{0, 30000, gain}, Case{1e-9, 0, 0}, Case{1e-9, 0, gain}}) {
        SolverOptions o;
        o.epsilon = 1e-4;
        o.refineSeconds = c.seconds;
        o.maxLinks = c.maxLinks;
        o.perLightOracle = c.perLight;
        o.narrowClusterSources = c.narrow;
        const auto t0 = std::chrono::steady_clock::now();
        HierarchicalSolver solver(scene, o);
        solver.solve();
        const double solveSeconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        std::printf(
            "refineSeconds %g, maxLinks %zu, perLightOracle %g, narrowed sources %s: "
            "solve %.3f s\n",
            c.seconds, c.maxLinks, c.perLight, c.narrow ? "on" : "off", solveSeconds);
        const LightResponses R(solver);
        const auto& nodes = solver.hierarchy().nodes;
        double inside = 0, outside = 0, areaIn = 0, areaOut = 0;
        for (size_t n = 0; n < nodes.size(); ++n) {
            const Node& e = nodes[n];
            if (e.isCluster() || !e.isLeaf()) continue;
            const int obj = scene.polygons[e.polygon].object;
            const double r = R.reflected(static_cast<int>(n))[1].maxComponent();
            (obj == 4 ? inside : outside) += r * e.area;
            (obj == 4 ? areaIn : areaOut) += e.area;
        }
        // Which links carry the lamp's light out: those whose source holds inner faces
        // and whose receiver holds none, by the source's kind.
        std::vector<char> in(nodes.size(), 0), out(nodes.size(), 0);
        for (size_t n = nodes.size(); n-- > 0;) {
            const Node& e = nodes[n];
            if (!e.isCluster() && e.isLeaf()) {
                const int obj = scene.polygons[e.polygon].object;
                in[n] = obj == 4;
                out[n] = obj != 4 && obj != 5;
            }
        }
        for (int pass = 0; pass < 64; ++pass)
            for (size_t n = 0; n < nodes.size(); ++n)
                for (int k = 0; k < nodes[n].childCount; ++k) {
                    in[n] |= in[nodes[n].firstChild + k];
                    out[n] |= out[nodes[n].firstChild + k];
                }
        double viaCluster = 0, viaElement = 0;
        int nc = 0, ne = 0;
        for (const Link& l : solver.links()) {
            if (!in[l.source] || in[l.receiver]) continue;
            const double t = l.F * static_cast<double>(l.V) *
                             R.reflected(l.source)[1].maxComponent() * nodes[l.receiver].area;
            if (nodes[l.source].isCluster()) {
                viaCluster += t;
                ++nc;
            } else {
                viaElement += t;
                ++ne;
            }
        }
        // Against what the lamp emits: pi L A for its 10 cm quad at unit radiance.
        const double emitted = 3.141592653589793 * 0.01;
        std::printf(
            "  out of the shade: %d links from clusters carry %.4g (%.2f %% of the lamp's "
            "power), %d from elements %.4g\n",
            nc, viaCluster, 100 * viaCluster / emitted, ne, viaElement);
        // Gather at the middle of each outward face.
        double gathered = 0;
        for (size_t p = 0; p < scene.polygons.size(); ++p) {
            if (scene.polygons[p].object != 3) continue;
            Rgb H[2];
            rayGatherResponses(solver, R, static_cast<int>(p), scene.polygons[p].centroid(), H, 8,
                               p);
            gathered = std::max(gathered, H[1].maxComponent());
        }
        // The light the outside's surfaces receive from the lamp, all bounces: what they
        // reflect over their reflectance (0.5 everywhere).
        std::printf(
            "  links %d; the lamp's reflected radiosity inside %.4g, "
            "outside %.4g (area means); the outside receives %.2f %% of the lamp's power; "
            "outward gather max %.4g\n",
            solver.stats().links, inside / areaIn, outside / areaOut, 100 * outside / 0.5 / emitted,
            gathered);
    }
    return 0;
}
