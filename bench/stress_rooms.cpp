// stress_rooms: the hierarchical solver on generated furnished rooms
// (tests/support/stress_room.h), one seed after another.
//
//   ./build/bench/stress_rooms [--seeds N] [--first S] [--epsilon E] [--time-limit SEC]
//                              [--mem-limit GB] [--write DIR] [--no-solve]
//
// Seeds S, S+1, ..., S+N-1 (default 1..100), each room drawn by
// stress::stressOptionsForSeed (quads or triangle grids, jitter, scale 2 mm..20, rotation)
// and solved in a forked child, twice: on 1 thread, then on 2. A child past --time-limit
// (default 60 s, both solves together) is killed by SIGALRM and reported as TIMEOUT with
// the last progress message of its solver; one past --mem-limit (default 4 GB of address
// space) fails its allocation and is reported as OOM: a runaway seed never hangs the
// bench nor takes the machine's memory. Per seed: polygons, lights, scale, both solve
// times, the child's peak resident memory (getrusage of the child: the whole process,
// about 10 MB of it before the solve), leaves, links, sweeps, refinement rounds, the
// energy balance (absorbed / emitted power, worst channel: at most 1 in a closed room),
// whether any node's B is NaN or infinite, and whether the 1- and 2-thread solutions are
// bit-identical (every node's B). --write DIR also writes each seed's scene package to
// DIR/seed_<S> (for `relight solve DIR/seed_<S>`); --no-solve only writes them.
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "bench/bench_util.h"
#include "radiosity/solver.h"
#include "radiosity/stopwatch.h"
#include "tests/support/stress_room.h"

using namespace radiosity;
using radiosity::Clock;
using radiosity::secondsSince;

namespace {

struct Args {
    int seeds = 100;
    int first = 1;
    double epsilon = 1e-3;
    int timeLimit = 60;    ///< seconds per seed, both solves
    double memLimit = 4;   ///< GB of address space per child
    std::string writeDir;  ///< empty: write nothing
    bool solve = true;
};

/// What a child reports, through memory shared with the parent (so that a child killed
/// by its alarm still leaves its last progress message).
struct Report {
    enum Status { running, ok, oom, error } status = running;
    double seconds1 = 0, seconds2 = 0;
    int leaves = 0, links = 0, sweeps = 0, rounds = 0;
    double balance = 0;  ///< absorbed / emitted, worst channel
    bool nonFinite = false, identical = false;
    char message[200] = {};  ///< the solver's last progress line, or the error
};

void setMessage(Report& r, const std::string& m) {
    std::snprintf(r.message, sizeof r.message, "%s", m.c_str());
}

/// One solve with `threads` threads; every node's B in `B`.
SolverStats solve(const Scene& scene, double epsilon, int threads, Report& report,
                  std::vector<Rgb>& B, double& seconds) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    SolverOptions o;
    o.epsilon = epsilon;
    o.maxRefineRounds = 8;
    o.progress = [&report, threads](const std::string& m) {
        setMessage(report, "last: " + std::to_string(threads) + " thread(s), " + m);
    };
    const auto t0 = Clock::now();
    HierarchicalSolver solver(scene, o);
    solver.solve();
    seconds = secondsSince(t0);
    B.clear();
    for (const Node& n : solver.hierarchy().nodes) B.push_back(n.B);
    return solver.stats();
}

/// The child's work: both solves and their comparison, into `r`.
void solveSeed(const stress::StressRoom& room, const Args& a, Report& r) {
    std::vector<Rgb> B1, B2;
    const SolverStats st = solve(room.scene, a.epsilon, 1, r, B1, r.seconds1);
    r.leaves = st.leaves;
    r.links = st.links;
    r.sweeps = st.sweeps;
    r.rounds = st.refineRounds;
    for (int k = 0; k < 3; ++k) {
        const double b = st.absorbedPower[k] / st.emittedPower[k];
        r.balance = std::isnan(b) || std::isnan(r.balance) ? b : std::max(r.balance, b);
    }
    for (const Rgb& b : B1) r.nonFinite = r.nonFinite || !b.isFinite();
    solve(room.scene, a.epsilon, 2, r, B2, r.seconds2);
    // Bit-identical: the bytes, so that a NaN reproduced by both runs counts as the same
    // (the NaN column says whether there is one).
    r.identical =
        B1.size() == B2.size() && std::memcmp(B1.data(), B2.data(), B1.size() * sizeof(Rgb)) == 0;
    r.status = Report::ok;
}

/// Runs solveSeed in a child under the time and memory limits; `maxrssKb` is the child's
/// peak resident memory. Returns the status word for the table.
std::string runChild(const stress::StressRoom& room, const Args& a, Report& shared,
                     long& maxrssKb) {
    shared = Report{};
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid < 0) return "FORK FAILED";
    if (pid == 0) {
        alarm(static_cast<unsigned>(a.timeLimit));
        const rlim_t bytes = static_cast<rlim_t>(a.memLimit * 1024 * 1024 * 1024);
        const rlimit lim{bytes, bytes};
        setrlimit(RLIMIT_AS, &lim);
        try {
            solveSeed(room, a, shared);
        } catch (const std::bad_alloc&) {
            shared.status = Report::oom;
        } catch (const std::exception& e) {
            shared.status = Report::error;
            setMessage(shared, e.what());
        }
        _exit(0);
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    maxrssKb = usage.ru_maxrss;
    if (WIFSIGNALED(status)) {
        const int sig = WTERMSIG(status);
        return sig == SIGALRM ? "TIMEOUT" : std::string("SIGNAL ") + strsignal(sig);
    }
    switch (shared.status) {
        case Report::ok:
            return "ok";
        case Report::oom:
            return "OOM";
        case Report::error:
            return "ERROR";
        case Report::running:
            break;
    }
    return "NO REPORT";
}

std::string meshName(const stress::StressRoomOptions& o) {
    if (!o.triangles) return "quads";
    return "tri" + std::to_string(o.grid) + (o.jitter > 0 ? "+j" : "");
}

bool parse(int argc, char** argv, Args& a) {
    for (int i = 1; i < argc; ++i) {
        const std::string k = argv[i];
        const bool value = i + 1 < argc;
        if (k == "--seeds" && value)
            a.seeds = std::atoi(argv[++i]);
        else if (k == "--first" && value)
            a.first = std::atoi(argv[++i]);
        else if (k == "--epsilon" && value)
            a.epsilon = std::atof(argv[++i]);
        else if (k == "--time-limit" && value)
            a.timeLimit = std::atoi(argv[++i]);
        else if (k == "--mem-limit" && value)
            a.memLimit = std::atof(argv[++i]);
        else if (k == "--write" && value)
            a.writeDir = argv[++i];
        else if (k == "--no-solve")
            a.solve = false;
        else
            return false;
    }
    return a.seeds > 0 && a.first >= 0 && a.epsilon > 0 && a.timeLimit > 0 && a.memLimit > 0;
}

struct Totals {
    int ok = 0, timeout = 0, failed = 0, overBalance = 0, nonFinite = 0, different = 0;
    std::vector<double> seconds;
};

void printRow(uint64_t seed, const stress::StressRoom& room, const std::string& status,
              const Report& r, long maxrssKb, Totals& t) {
    const auto& o = room.options;
    std::printf("%6llu %-7s %7zu %6zu %8.4g %-9s", static_cast<unsigned long long>(seed),
                meshName(o).c_str(), room.scene.polygons.size(), room.scene.lights.size(), o.scale,
                status.c_str());
    const double mb = static_cast<double>(maxrssKb) / 1024;
    if (status != "ok") {
        std::printf(" %8s %8s %8.0f   %s\n", "-", "-", mb, r.message);
        (status == "TIMEOUT" ? t.timeout : t.failed)++;
        return;
    }
    std::printf(" %8.3f %8.3f %8.0f %8d %9d %6d %6d %9.4f %4s %5s\n", r.seconds1, r.seconds2, mb,
                r.leaves, r.links, r.sweeps, r.rounds, r.balance, r.nonFinite ? "yes" : "no",
                r.identical ? "yes" : "NO");
    ++t.ok;
    t.seconds.push_back(r.seconds1);
    t.overBalance += r.balance > 1.01;
    t.nonFinite += r.nonFinite;
    t.different += !r.identical;
}

}  // namespace

int main(int argc, char** argv) {
    Args a;
    if (!parse(argc, argv, a)) {
        std::fprintf(stderr,
                     "usage: %s [--seeds N] [--first S] [--epsilon E] [--time-limit SEC] "
                     "[--mem-limit GB] [--write DIR] [--no-solve]\n",
                     argv[0]);
        return 2;
    }
    std::printf("command:");
    for (int i = 0; i < argc; ++i) std::printf(" %s", argv[i]);
    std::printf("\nseeds %d..%d, epsilon %g, maxRefineRounds 8, limits %d s and %g GB per seed\n",
                a.first, a.first + a.seeds - 1, a.epsilon, a.timeLimit, a.memLimit);
    // The report lives in memory shared with the children (it survives their kill).
    void* mem =
        mmap(nullptr, sizeof(Report), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (mem == MAP_FAILED) {
        std::perror("mmap");
        return 1;
    }
    Report& shared = *new (mem) Report{};
    std::printf("%6s %-7s %7s %6s %8s %-9s %8s %8s %8s %8s %9s %6s %6s %9s %4s %5s\n", "seed",
                "mesh", "polys", "lights", "scale", "status", "1 thr s", "2 thr s", "peak MB",
                "leaves", "links", "sweeps", "rounds", "abs/emit", "NaN", "1=2");
    Totals totals;
    for (int i = 0; i < a.seeds; ++i) {
        const uint64_t seed = static_cast<uint64_t>(a.first + i);
        const stress::StressRoom room = stress::makeStressRoom(stress::stressOptionsForSeed(seed));
        if (!a.writeDir.empty())
            stress::writeStressRoomPackage(room, a.writeDir + "/seed_" + std::to_string(seed));
        if (!a.solve) continue;
        long maxrssKb = 0;
        const std::string status = runChild(room, a, shared, maxrssKb);
        printRow(seed, room, status, shared, maxrssKb, totals);
    }
    if (!a.writeDir.empty()) std::printf("scene packages in %s/seed_<S>\n", a.writeDir.c_str());
    if (!a.solve) return 0;
    std::printf(
        "\n%d solved, %d TIMEOUT, %d failed otherwise; of the solved: %d absorbed more than "
        "1.01 x emitted, %d with NaN/Inf, %d differ between 1 and 2 threads; median 1-thread "
        "solve %.3f s\n",
        totals.ok, totals.timeout, totals.failed, totals.overBalance, totals.nonFinite,
        totals.different, bench::quantile(totals.seconds, 0.5));
    return 0;
}
