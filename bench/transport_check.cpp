// Whether the hierarchy's links carry the light its radiosities imply: for each leaf, the
// indirect irradiance it gathered through the links (B = E + rho (Hd + Hx + H)) against a
// ray gather of the same leaves' radiosities at its centre (radiosity/final_gather.h,
// rayGatherIndirect: cosine-distributed rays, each reading the B - E of the leaf it hits).
// A converged solution whose links were right has the two equal up to the rays' noise; a
// transport that loses light shows links / rays < 1.
//   ./build/bench/transport_check <scene_dir> [epsilon]     (the scene's reflectances: use
//   a scene.json with "objects" reflectances; the photo is not read)
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "radiosity/final_gather.h"
#include "radiosity/solver.h"
#include "relight/io/scene_file.h"

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: transport_check SCENE_DIR [EPSILON]\n");
        return 2;
    }
    relight::SceneFile sf = relight::loadScene(argv[1]);
    radiosity::SolverOptions o;
    o.epsilon = argc > 2 ? std::atof(argv[2]) : 1e-4;
    radiosity::HierarchicalSolver solver(sf.scene, o);
    solver.solve();
    const auto& nodes = solver.hierarchy().nodes;
    const auto& scene = solver.scene();
    struct Sum {
        double area = 0, links = 0, rays = 0, hx = 0;
    };
    std::map<std::string, Sum> by;
    for (size_t n = 0; n < nodes.size(); ++n) {
        const radiosity::Node& e = nodes[n];
        if (e.isCluster() || !e.isLeaf() || !(e.rho.g > 0)) continue;
        const double H = (e.B.g - e.E.g) / e.rho.g - e.Hx.g - e.Hd.g;
        const radiosity::Rgb R =
            radiosity::rayGatherIndirect(solver, e.polygon, e.centre, 24, 7 + n);
        const auto& poly = scene.polygons[static_cast<size_t>(e.polygon)];
        std::string name = poly.object >= 0 ? scene.objects[static_cast<size_t>(poly.object)] : "?";
        Sum& s = by[name];
        s.area += e.area;
        s.links += H * e.area;
        s.rays += R.g * e.area;
        s.hx += e.Hx.g * e.area;
        if (e.seen < 0.5) {
            Sum& b = by["(seen<0.5)"];
            b.area += e.area;
            b.links += H * e.area;
            b.rays += R.g * e.area;
            b.hx += e.Hx.g * e.area;
        }
        Sum& t = by["(all)"];
        t.area += e.area;
        t.links += H * e.area;
        t.rays += R.g * e.area;
        t.hx += e.Hx.g * e.area;
    }
    std::printf("command: transport_check %s %g\n", argv[1], o.epsilon);
    std::printf("%-14s %9s %12s %12s %12s %8s\n", "object", "area_m2", "Hx_A", "H_links_A",
                "H_rays_A", "links/rays");
    for (const auto& [name, s] : by)
        std::printf("%-14s %9.3f %12.5f %12.5f %12.5f %8.4f\n", name.c_str(), s.area, s.hx, s.links,
                    s.rays, s.rays > 0 ? s.links / s.rays : 0.0);
}
