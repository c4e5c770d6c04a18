// surface_levels: the hierarchical solution's level on each input polygon against the
// full-matrix reference (radiosity/reference_solver.h), the scene's own reflectances.
//
//   surface_levels <scene_dir> [--ref-area A] [--dark-floor F] [--no-balance]
//                  [--read leaf|final|ray] [epsilons...]
//
// --ref-area: the reference's largest element (m^2, default 0.002); --dark-floor:
// SolverOptions::darkFloor (default 1, the plain criterion); --no-balance: without the
// balance of sends (SolverOptions::balanceSends); --read: the solution read as its leaves
// hold it (default), by the final gather through the links at each point, or by a ray
// gather of the leaves' radiosities with the direct light per point (readAt).
// For each epsilon (default 1e-4 1e-5), per input polygon that reflects: its centroid,
// normal, area, and the ratio of the area mean of B (all channels) over it, hierarchical
// against reference, read at the reference's elements (4 x 4 points each). A ratio below 1
// is light the hierarchy loses on that surface; the area-weighted total says whether the
// loss is overall or moves light from one surface to another.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "radiosity/final_gather.h"
#include "radiosity/reference_solver.h"
#include "radiosity/solver.h"
#include "relight/io/scene_file.h"

using namespace radiosity;

namespace {

double sum3(const Rgb& c) {
    return c.r + c.g + c.b;
}

/// Area-weighted sum of B over each polygon's reference elements, for B read by `at`.
std::vector<double> perPolygon(const ReferenceSolver& ref, size_t polygons,
                               const std::function<Rgb(int, const Vec3&)>& at) {
    std::vector<double> sums(polygons, 0.0);
    const Hierarchy& h = ref.hierarchy();
    for (int id : ref.leaves()) {
        const Node& e = h.nodes[id];
        if (e.rho.maxComponent() <= 0 || e.polygon < 0) continue;
        sums[static_cast<size_t>(e.polygon)] += e.area * sum3(elementMean(e, at));
    }
    return sums;
}

/// B at x as a display reads it: "final", the final gather through the links
/// (gatheredRadiosity); "ray", the direct light per point and the leaves' radiosities met by
/// 16 x 16 cosine rays (rayGatherIndirect).
Rgb readAt(const HierarchicalSolver& hr, const DirectLight& direct, const std::string& read, int p,
           const Vec3& x, uint64_t seed) {
    if (read == "final") return gatheredRadiosity(hr, direct, p, x, seed);
    const Scene& scene = hr.scene();
    const Rgb H = direct.irradiance(p, x, seed) + rayGatherIndirect(hr, p, x, 16, seed);
    return scene.emittance(p) + scene.polygons[static_cast<size_t>(p)].rho * H;
}

/// argv[i] as a positive finite number, or exits with a message naming `what`.
double positive(const char* arg, const char* what) {
    char* end = nullptr;
    const double v = arg ? std::strtod(arg, &end) : 0.0;
    if (!arg || end == arg || *end != '\0' || !(v > 0) || !std::isfinite(v)) {
        std::fprintf(stderr, "surface_levels: %s: expected a positive number, got '%s'\n", what,
                     arg ? arg : "");
        std::exit(2);
    }
    return v;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr,
                     "usage: %s <scene_dir> [--ref-area A] [--dark-floor F] [--no-balance] [--read "
                     "leaf|final|ray] [epsilons...]\n",
                     argv[0]);
        return 2;
    }
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\n");
    double refArea = 0.002, darkFloor = 1.0;
    bool balance = true;
    std::string read = "leaf";
    std::vector<double> eps;
    for (int i = 2; i < argc; ++i) {
        const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
        if (!std::strcmp(argv[i], "--ref-area"))
            refArea = positive(next, "--ref-area"), ++i;
        else if (!std::strcmp(argv[i], "--dark-floor"))
            darkFloor = positive(next, "--dark-floor"), ++i;
        else if (!std::strcmp(argv[i], "--no-balance"))
            balance = false;
        else if (!std::strcmp(argv[i], "--read") && next)
            read = argv[++i];
        else
            eps.push_back(positive(argv[i], "epsilon"));
    }
    if (eps.empty()) eps = {1e-4, 1e-5};
    if (read != "leaf" && read != "final" && read != "ray") {
        std::fprintf(stderr, "surface_levels: --read %s: expected leaf, final or ray\n",
                     read.c_str());
        return 2;
    }
    try {
        const auto sf = relight::loadScene(argv[1]);
        const Scene& scene = sf.scene;
        ReferenceOptions ro;
        ro.maxArea = refArea;
        ReferenceSolver ref(scene, ro);
        ref.solve();
        std::printf("reference: %zu elements of at most %g m^2\n", ref.leaves().size(), refArea);
        const auto refSums = perPolygon(ref, scene.polygons.size(), [&](int p, const Vec3& x) {
            return ref.radiosityAt(p, x);
        });
        for (double e : eps) {
            SolverOptions o;
            o.epsilon = e;
            o.darkFloor = darkFloor;
            o.balanceSends = balance;
            HierarchicalSolver hr(scene, o);
            hr.solve();
            const DirectLight direct(hr);
            uint64_t seed = 0;
            const auto sums = perPolygon(ref, scene.polygons.size(), [&](int p, const Vec3& x) {
                return read == "leaf" ? hr.radiosityAt(p, x)
                                      : readAt(hr, direct, read, p, x, ++seed);
            });
            std::printf("\nepsilon %g: %d links\n", e, hr.stats().links);
            std::printf("%5s %26s %22s %8s %8s\n", "poly", "centroid", "normal", "area",
                        "hier/ref");
            double all = 0, allRef = 0;
            for (size_t p = 0; p < sums.size(); ++p) {
                if (!(refSums[p] > 0)) continue;
                const Polygon& q = scene.polygons[p];
                const Vec3 c = q.centroid(), n = q.normal;
                std::printf("%5zu (%7.3f %7.3f %7.3f) (%5.2f %5.2f %5.2f) %8.4f %8.4f\n", p, c.x,
                            c.y, c.z, n.x, n.y, n.z, q.area, sums[p] / refSums[p]);
                all += sums[p];
                allRef += refSums[p];
            }
            std::printf("all: %.4f\n", all / allRef);
        }
    } catch (const std::exception& ex) {
        std::fprintf(stderr, "surface_levels: %s\n", ex.what());
        return 1;
    }
    return 0;
}
