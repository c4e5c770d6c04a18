// Rng: splitmix64 (Steele, Lea & Flood 2014), a small well-mixed generator. Every user
// seeds it from what it samples (two node ids, a pixel sample index), so that results do
// not depend on the order of evaluation or on the thread count.
#pragma once

#include <cstdint>

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

}  // namespace radiosity
