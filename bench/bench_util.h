// Small helpers the benchmark programs share.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace bench {

/// The q-quantile of v (the element at rank q n, no interpolation); 0 when v is empty.
inline double quantile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
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
