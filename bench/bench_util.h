// Small helpers the benchmark programs share.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace bench {

using Clock = std::chrono::steady_clock;

/// Seconds since t0.
inline double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// The arguments of the relighting benches, `<data_dir> [--epsilon E]`: false (after a
/// usage line on stderr) when they are missing; else prints the command that makes the
/// figures, as every bench does.
inline bool parseDataAndEpsilon(int argc, char** argv, std::string& data, double& epsilon) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s <data_dir> [--epsilon E]\n", argv[0]);
        return false;
    }
    data = argv[1];
    if (argc > 3 && std::strcmp(argv[2], "--epsilon") == 0) epsilon = std::atof(argv[3]);
    std::printf("command: %s %s --epsilon %g\n", argv[0], data.c_str(), epsilon);
    return true;
}

}  // namespace bench
