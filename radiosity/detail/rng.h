// Rng: splitmix64 (Steele, Lea & Flood 2014), a small well-mixed generator. Every user
// seeds it from what it samples (two node ids, a pixel sample index), so that results do
// not depend on the order of evaluation or on the thread count.
#pragma once

#include <cstdint>
#include <utility>

namespace radiosity {

struct Rng {
    uint64_t state;
    explicit Rng(uint64_t seed) : state(seed) {}
    uint64_t next() {
        uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    /// Uniform in [0, 1).
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

/// The side k of the smallest k x k grid of strata with at least n cells.
inline int strataSide(int n) {
    int k = 1;
    while (k * k < n) ++k;
    return k;
}

/// perm[0, k*k) = the cells of a k x k grid in random order (Fisher-Yates), so that any
/// prefix of it spreads over the whole square: a first round of rays taken from the
/// front of the list is a fair sample, and later rounds continue it.
inline void shuffledStrata(Rng& rng, int k, int* perm) {
    const int cells = k * k;
    for (int i = 0; i < cells; ++i) perm[i] = i;
    for (int i = cells - 1; i > 0; --i)
        std::swap(perm[i], perm[static_cast<int>(rng.next() % static_cast<uint64_t>(i + 1))]);
}

}  // namespace radiosity
