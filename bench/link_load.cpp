// link_load: where a solution's links pile up. A point's final gather reads the links of its
// leaf and of every node above it (radiosity/shared_gather.h): its cost follows that chain's
// link count, not the scene's size. This prints the chain counts' distribution over the
// leaves and the leaves of the longest chains, with their objects and the objects their
// links come from.
//
//   ./build/bench/link_load <scene_dir> [--time-budget S]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "relight/io/scene_file.h"

using namespace radiosity;

namespace {

/// The object a node's surfaces belong to ("(cluster)" for a cluster over several).
std::string objectOf(const HierarchicalSolver& s, int node) {
    const Hierarchy& h = s.hierarchy();
    const Node& n = h.nodes[static_cast<size_t>(node)];
    int p = n.polygon;
    if (p < 0 && n.polyEnd > n.polyBegin) {
        const int first = h.polygonOrder[static_cast<size_t>(n.polyBegin)];
        const int last = h.polygonOrder[static_cast<size_t>(n.polyEnd - 1)];
        const int a = s.scene().polygons[static_cast<size_t>(first)].object;
        if (a != s.scene().polygons[static_cast<size_t>(last)].object) return "(cluster)";
        p = first;
    }
    if (p < 0) return "(none)";
    const int o = s.scene().polygons[static_cast<size_t>(p)].object;
    return o >= 0 ? s.scene().objects[static_cast<size_t>(o)] : "(no object)";
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <scene_dir> [--time-budget S]\n", argv[0]);
        return 2;
    }
    double budget = 30;
    for (int i = 2; i + 1 < argc; ++i)
        if (std::strcmp(argv[i], "--time-budget") == 0) budget = std::atof(argv[i + 1]);
    std::printf("command: %s %s --time-budget %g\n", argv[0], argv[1], budget);
    relight::SceneFile sf = relight::loadScene(argv[1]);
    SolverOptions o;
    o.refineSeconds = budget * 0.5;
    HierarchicalSolver s(sf.scene, o);
    s.solve();
    const Hierarchy& h = s.hierarchy();
    // Per node, the links of the chain from it up to the root.
    std::vector<size_t> chain(h.nodes.size(), 0);
    std::vector<int> leaves;
    for (size_t n = 0; n < h.nodes.size(); ++n) {
        for (int m = static_cast<int>(n); m >= 0; m = h.nodes[static_cast<size_t>(m)].parent)
            chain[n] += s.linksOf(m).size();
        if (h.nodes[n].isLeaf() && !h.nodes[n].isCluster()) leaves.push_back(static_cast<int>(n));
    }
    std::sort(leaves.begin(), leaves.end(), [&](int a, int b) {
        return chain[static_cast<size_t>(a)] > chain[static_cast<size_t>(b)];
    });
    size_t total = 0;
    for (int l : leaves) total += chain[static_cast<size_t>(l)];
    std::printf("leaves %zu, links %zu, chain links summed over the leaves %zu (mean %.1f)\n",
                leaves.size(), s.links().size(), total,
                leaves.empty() ? 0.0 : static_cast<double>(total) / leaves.size());
    for (double q : {0.5, 0.9, 0.99, 0.999}) {
        const size_t i = static_cast<size_t>((1 - q) * leaves.size());
        if (i < leaves.size())
            std::printf("  %.1f %% of the leaves have chains of at most %zu links\n", 100 * q,
                        chain[static_cast<size_t>(leaves[i])]);
    }
    size_t top = 0;
    const size_t shown = std::min<size_t>(leaves.size(), 100);
    for (size_t i = 0; i < shown; ++i) top += chain[static_cast<size_t>(leaves[i])];
    std::printf("the %zu longest chains hold %.1f %% of the sum\n", shown,
                total > 0 ? 100.0 * top / total : 0.0);
    for (size_t i = 0; i < std::min<size_t>(leaves.size(), 8); ++i) {
        const int leaf = leaves[i];
        std::map<std::string, size_t> from;
        size_t own = s.linksOf(leaf).size();
        for (int n = leaf; n >= 0; n = h.nodes[static_cast<size_t>(n)].parent)
            for (const Link& l : s.linksOf(n)) ++from[objectOf(s, l.source)];
        std::printf(
            "leaf %d (%s, area %.3g m^2, level %d): %zu links in its chain, %zu its own;"
            " sources:",
            leaf, objectOf(s, leaf).c_str(), h.nodes[static_cast<size_t>(leaf)].area,
            h.nodes[static_cast<size_t>(leaf)].level, chain[static_cast<size_t>(leaf)], own);
        for (const auto& [name, count] : from) std::printf(" %s %zu", name.c_str(), count);
        std::printf("\n");
    }
    return 0;
}
