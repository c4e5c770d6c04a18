// Where a solve's links and leaves go, per object: the scene's radiosity solution of its
// photo's lights (the lights as scene.json gives them), refined for a given number of
// rounds, then counted by the receiver's object: polygons, leaf elements, active links
// received (of them from a lamp's face, from a cluster, cluster receivers), and the solve's
// time per phase. Used to see which part of a real mesh makes the links grow.
//
//   ./build/bench/solve_anatomy <scene_dir> [--epsilon 1e-4] [--rounds 8]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "radiosity/face_clusters.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/io/scene_file.h"

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <scene_dir> [--epsilon E] [--rounds N]\n", argv[0]);
        return 2;
    }
    double epsilon = 1e-4;
    int rounds = 8;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--epsilon") == 0) epsilon = std::atof(argv[i + 1]);
        if (std::strcmp(argv[i], "--rounds") == 0) rounds = std::atoi(argv[i + 1]);
    }
    std::printf("command: %s %s --epsilon %g --rounds %d\n", argv[0], argv[1], epsilon, rounds);
    const relight::SceneFile sf = relight::loadScene(argv[1]);
    radiosity::SolverOptions so;
    so.epsilon = epsilon;
    so.maxRefineRounds = rounds;
    const auto t0 = radiosity::Clock::now();
    so.progress = [&](const std::string& m) {
        std::printf("%8.1f s  %s\n", radiosity::secondsSince(t0), m.c_str());
        std::fflush(stdout);
    };
    {
        const auto tf = radiosity::Clock::now();
        const radiosity::FaceClusterForest forest = radiosity::buildFaceClusters(sf.scene.polygons);
        std::map<std::string, std::pair<long, long>> patches;  // object -> (patches, polygons)
        std::vector<int> members;
        long single = 0;
        for (int root : forest.roots) {
            members.clear();
            forest.polygonsUnder(root, members);
            auto& row = patches[sf.scene.objects[sf.scene.polygons[members[0]].object]];
            ++row.first;
            row.second += static_cast<long>(members.size());
            single += members.size() == 1;
        }
        std::printf("face clusters: %zu patches (%ld of one polygon) over %zu polygons, %.2f s\n",
                    forest.roots.size(), single, sf.scene.polygons.size(),
                    radiosity::secondsSince(tf));
        for (const auto& [name, row] : patches)
            std::printf("  %-22s %8ld patches, %9ld polygons\n", name.c_str(), row.first,
                        row.second);
    }
    radiosity::HierarchicalSolver solver(sf.scene, so);
    std::printf("%8.1f s  built: %zu polygons, %d clusters\n", radiosity::secondsSince(t0),
                sf.scene.polygons.size(), solver.hierarchy().clusterCount());
    solver.solve();
    const auto& h = solver.hierarchy();
    const auto& scene = solver.scene();
    struct Row {
        long polygons = 0, leaves = 0, links = 0, fromLamp = 0, fromCluster = 0, toCluster = 0;
    };
    std::map<std::string, Row> rows;
    const auto objectOf = [&](int node) -> std::string {
        const radiosity::Node& n = h.nodes[node];
        if (n.isCluster()) {
            const int p = h.polygonOrder[n.polyBegin];
            const int q = h.polygonOrder[n.polyEnd - 1];
            const int o = scene.polygons[p].object;
            return o == scene.polygons[q].object ? scene.objects[o] : "(mixed clusters)";
        }
        return scene.objects[scene.polygons[n.polygon].object];
    };
    for (const auto& p : scene.polygons) ++rows[scene.objects[p.object]].polygons;
    for (size_t i = 0; i < h.nodes.size(); ++i)
        if (!h.nodes[i].isCluster() && h.nodes[i].isLeaf()) ++rows[objectOf(int(i))].leaves;
    for (const radiosity::Link& l : solver.links()) {
        Row& r = rows[objectOf(l.receiver)];
        ++r.links;
        const radiosity::Node& S = h.nodes[l.source];
        if (!S.isCluster() && S.emitting) ++r.fromLamp;
        if (S.isCluster()) ++r.fromCluster;
        if (h.nodes[l.receiver].isCluster()) ++r.toCluster;
    }
    std::printf("%-24s %9s %9s %10s %10s %10s %10s\n", "receiver object", "polygons", "leaves",
                "links", "from lamp", "from clus", "to clus");
    for (const auto& [name, r] : rows)
        std::printf("%-24s %9ld %9ld %10ld %10ld %10ld %10ld\n", name.c_str(), r.polygons, r.leaves,
                    r.links, r.fromLamp, r.fromCluster, r.toCluster);
    const auto st = solver.stats();
    std::printf(
        "links %d (passive %d), leaves %d, rays %llu, refine %.1f s, gather %.1f s, "
        "push-pull %.1f s, build %.1f s, total %.1f s\n",
        st.links, st.passiveLinks, st.leaves, static_cast<unsigned long long>(st.rays),
        st.timeRefine, st.timeGather, st.timePushPull, st.timeBuild, radiosity::secondsSince(t0));
    return 0;
}
