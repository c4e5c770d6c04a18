// Preparation against the size of the mesh: the bundled room with every face that is not a
// lamp cut into an N x N grid of triangle pairs (as a reconstruction gives it), with and
// without jitter of the interior vertices along the face's normal.
//
//   ./build/bench/mesh_size data [--cuts 1,2,4,16,50,150] [--jitter 0.002] [--epsilon 1e-4]
//                                [--plot bench/figures/mesh_size_links.png]
//
// For each cut N and each jitter (0 and --jitter), a child process (this program again,
// with --one) cuts the room in memory, prepares it (the whole pipeline, relight prepare)
// and renders the room's five light edits, each scored against data/room/truth by the
// spec's metric; it prints the triangles, the preparation's time and its solve part, the
// peak resident memory (getrusage maxrss of the child), the leaves and links, whether the
// refinement budget was reached, and rel_rmse per edit. The parent prints the table, the
// difference of each cut room's scores from the plain room's, and a log-log plot of the
// links against the triangles, with n log n through the first point for comparison.
//
// The cutting: corners on the face's bilinear map; each interior grid vertex moves along
// the face's normal by jitter * u, u uniform in [-1, 1] from a generator seeded by the
// vertex's grid position and face, so that the two faces of an edge (boundary vertices
// never move) stay joined.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "bench/plot.h"
#include "radiosity/detail/rng.h"
#include "radiosity/stopwatch.h"
#include "relight/display/metric.h"
#include "relight/io/edit_file.h"
#include "relight/relighting.h"

using namespace relight;
using radiosity::Clock;
using radiosity::Polygon;
using radiosity::secondsSince;
using radiosity::Vec3;

namespace {

const char* const kEdits[] = {"identity", "back_off", "left_off_right_double",
                              "right_off_left_double", "colours"};

/// Cuts every polygon that is not a lamp's emitting face into cut x cut triangle pairs.
void cutScene(SceneFile& sf, int cut, double jitter) {
    radiosity::Scene& s = sf.scene;
    std::vector<Polygon> out;
    std::vector<int> newIndex(s.polygons.size(), -1);
    for (size_t p = 0; p < s.polygons.size(); ++p) {
        const Polygon& P = s.polygons[p];
        if (P.light >= 0 || cut <= 1) {
            newIndex[p] = static_cast<int>(out.size());
            out.push_back(P);
            continue;
        }
        const auto at = [&](int i, int j) {
            const double u = double(i) / cut, v = double(j) / cut;
            Vec3 x = P.vertexCount == 4
                         ? (1 - u) * (1 - v) * P.v[0] + u * (1 - v) * P.v[1] + u * v * P.v[2] +
                               (1 - u) * v * P.v[3]
                         // A triangle: the square's edge v = 1 collapses onto corner 2.
                         : (1 - u) * (1 - v) * P.v[0] + u * (1 - v) * P.v[1] + v * P.v[2];
            if (jitter > 0 && i > 0 && j > 0 && i < cut && j < cut) {
                radiosity::Rng rng(0xB0A7ull ^ (uint64_t(p) << 40) ^ (uint64_t(i) << 20) ^
                                   uint64_t(j));
                x += P.normal * (jitter * (2 * rng.uniform() - 1));
            }
            return x;
        };
        for (int i = 0; i < cut; ++i)
            for (int j = 0; j < cut; ++j) {
                const Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
                for (const auto& tri : {std::vector<Vec3>{a, b, c}, std::vector<Vec3>{a, c, d}}) {
                    const auto check = radiosity::checkPolygon(tri);
                    if (check.status != radiosity::PolygonCheck::Status::ok) continue;  // sliver
                    out.push_back(radiosity::makePolygon(tri, P.object, P.rho));
                }
            }
    }
    for (auto& light : s.lights)
        for (int& p : light.polygons) p = newIndex[p];
    s.polygons = std::move(out);
}

/// The child: one cut room, one line of results.
int runOne(const std::string& data, int cut, double jitter, double epsilon) {
    SceneFile sf = loadScene(data + "/room");
    cutScene(sf, cut, jitter);
    const size_t triangles = sf.scene.polygons.size();
    RelightOptions o;
    o.timeBudget = RelightOptions::kCommandTimeBudget;  // as the commands' default
    o.epsilon = epsilon;
    const auto t0 = Clock::now();
    const auto r = prepareRelighting(std::move(sf), o);
    const double prepare = secondsSince(t0);
    const auto st = r->solver->stats();
    std::ostringstream line;
    line << "RESULT " << cut << " " << jitter << " " << triangles << " " << prepare << " "
         << r->prepared.times.solve << " ";
    std::vector<double> scores;
    for (const char* name : kEdits) {
        const EditFile e = loadEdit(data + "/room/edits/" + name + ".json", r->scene);
        const Image img =
            renderEdit(r->prepared, editRadiance(r->scene, e, r->prepared.photoRadiance));
        int w = img.width, h = img.height;
        const Score sc =
            scoreImage(img, readImage(data + "/room/truth/" + name + ".exr"), r->prepared.photo,
                       readMask(data + "/room/truth/" + name + ".mask.png", w, h),
                       readMask(data + "/room/photo.mask.png", w, h));
        scores.push_back(sc.relRmse);
    }
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    line << ru.ru_maxrss / 1024.0 << " " << st.leaves << " " << st.links << " "
         << (st.budgetReached ? 1 : 0);
    for (double s : scores) line << " " << s;
    std::printf("%s\n", line.str().c_str());
    return 0;
}

struct Row {
    int cut = 0;
    double jitter = 0;
    size_t triangles = 0;
    double prepare = 0, solve = 0, peakMB = 0;
    int leaves = 0, links = 0, budget = 0;
    std::vector<double> scores;
    bool ok = false;
};

Row runChild(const char* self, const std::string& data, int cut, double jitter, double epsilon) {
    Row row;
    row.cut = cut;
    row.jitter = jitter;
    const std::string cmd = std::string(self) + " " + data + " --one " + std::to_string(cut) + " " +
                            std::to_string(jitter) + " " + std::to_string(epsilon) + " 2>/dev/null";
    FILE* f = popen(cmd.c_str(), "r");
    if (!f) return row;
    char buf[4096];
    while (std::fgets(buf, sizeof buf, f)) {
        if (std::strncmp(buf, "RESULT ", 7) != 0) continue;
        std::istringstream in(buf + 7);
        in >> row.cut >> row.jitter >> row.triangles >> row.prepare >> row.solve >> row.peakMB >>
            row.leaves >> row.links >> row.budget;
        double s;
        while (in >> s) row.scores.push_back(s);
        row.ok = row.scores.size() == std::size(kEdits);
    }
    pclose(f);
    return row;
}

std::vector<int> parseCuts(const std::string& s) {
    std::vector<int> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) out.push_back(std::atoi(item.c_str()));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc >= 6 && std::string(argv[2]) == "--one")
        return runOne(argv[1], std::atoi(argv[3]), std::atof(argv[4]), std::atof(argv[5]));
    if (argc < 2 || argv[1][0] == '-') {  // no data folder, or --help
        std::fprintf(stderr,
                     "usage: mesh_size DATA [--cuts 1,2,4,16,50,150] [--jitter 0.002] "
                     "[--epsilon 1e-4] [--plot FILE.png]\n");
        return 2;
    }
    const std::string data = argv[1];
    std::vector<int> cuts{1, 2, 4, 16, 50, 150};
    double jitter = 0.002, epsilon = 1e-4;
    std::string plot = "bench/figures/mesh_size_links.png";
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        if (a == "--cuts") cuts = parseCuts(argv[i + 1]);
        if (a == "--jitter") jitter = std::atof(argv[i + 1]);
        if (a == "--epsilon") epsilon = std::atof(argv[i + 1]);
        if (a == "--plot") plot = argv[i + 1];
    }
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf(
        "\nthe room with each non-lamp face cut N x N into triangle pairs; epsilon %g, "
        "2 threads; rel_rmse of the five light edits against data/room/truth\n\n",
        epsilon);
    std::printf("%5s %7s %9s %9s %8s %9s %8s %9s %6s", "N", "jitter", "triangles", "prepare s",
                "solve s", "peak MB", "leaves", "links", "budget");
    for (const char* e : kEdits) std::printf(" %10.10s", e);
    std::printf("\n");
    std::vector<Row> rows;
    for (int cut : cuts)
        for (double j : {0.0, jitter}) {
            if (cut == 1 && j > 0) continue;  // no interior vertex to move
            const Row r = runChild(argv[0], data, cut, j, epsilon);
            rows.push_back(r);
            if (!r.ok) {
                std::printf("%5d %7.4f  failed (ran out of time or memory, or crashed)\n", cut, j);
                continue;
            }
            std::printf("%5d %7.4f %9zu %9.2f %8.2f %9.0f %8d %9d %6s", r.cut, r.jitter,
                        r.triangles, r.prepare, r.solve, r.peakMB, r.leaves, r.links,
                        r.budget ? "yes" : "no");
            for (double s : r.scores) std::printf(" %10.4f", s);
            std::printf("\n");
            std::fflush(stdout);
        }
    if (!rows.empty() && rows.front().ok) {
        std::printf(
            "\nrel_rmse minus the plain room's (N = 1), per edit; the issue's bound 0.005:\n");
        for (const Row& r : rows) {
            if (!r.ok || r.cut == 1) continue;
            std::printf("%5d %7.4f", r.cut, r.jitter);
            double worst = 0;
            for (size_t e = 0; e < r.scores.size(); ++e) {
                const double d = r.scores[e] - rows.front().scores[e];
                worst = std::max(worst, std::abs(d));
                std::printf(" %+10.4f", d);
            }
            std::printf("   worst %.4f %s\n", worst, worst <= 0.005 ? "ok" : "OVER");
        }
    }
    std::vector<bench::Series> series(3);
    series[0] = {"links, no jitter", {0.1f, 0.3f, 0.8f}, {}};
    series[1] = {"links, jitter", {0.9f, 0.4f, 0.1f}, {}};
    series[2] = {"n log n (through the first point)", {0.5f, 0.5f, 0.5f}, {}};
    for (const Row& r : rows)
        if (r.ok)
            series[r.jitter > 0 ? 1 : 0].points.push_back({double(r.triangles), double(r.links)});
    if (!series[0].points.empty()) {
        const auto [n0, l0] = series[0].points.front();
        for (const Row& r : rows) {
            const double n = double(r.triangles);
            if (r.ok) series[2].points.push_back({n, l0 * n * std::log(n) / (n0 * std::log(n0))});
        }
        std::sort(series[2].points.begin(), series[2].points.end());
    }
    if (bench::plotLogLog(plot, series, "input triangles", "links"))
        std::printf("\nwrote %s\n", plot.c_str());
    return 0;
}
