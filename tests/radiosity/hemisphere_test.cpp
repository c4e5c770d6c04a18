// Stratified cosine-distributed directions (radiosity/detail/hemisphere.h), which the energy
// bound and the light reach cast, and the parallel loops (radiosity/parallel.h).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <vector>

#include "radiosity/detail/hemisphere.h"
#include "radiosity/parallel.h"

namespace radiosity {
namespace {

TEST(Hemisphere, DirectionsAreUnitAndInFrontOfTheNormal) {
    for (const Vec3 n : {Vec3{0, 0, 1}, Vec3{1, 0, 0}, glm::normalize(Vec3{-1, 2, -3})}) {
        const HemisphereFrame f(n);
        EXPECT_NEAR(glm::dot(f.t, f.b), 0.0, 1e-12);
        EXPECT_NEAR(glm::dot(f.t, n), 0.0, 1e-12);
        EXPECT_NEAR(glm::length(glm::cross(f.t, f.b) - n), 0.0, 1e-12);
        Rng rng(7);
        const int k = 12;
        for (int cell = 0; cell < k * k; ++cell) {
            const Vec3 d = cosineDirection(f, cell, k, rng);
            EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
            EXPECT_GE(glm::dot(d, n), 0.0);
        }
    }
}

TEST(Hemisphere, MomentsAreTheCosineDistributions) {
    // For p(w) = cos(theta) / pi: E[cos] = 2/3, E[cos^2] = 1/2, and the tangential mean is 0.
    // With k x k strata the estimate's error falls as 1/k^1.5 or faster; at k = 32 (1024
    // directions) 2e-3 is several times what stratified sampling leaves (about 3e-4 here),
    // yet a map that is not cosine-distributed (uniform: E[cos] = 1/2) fails by 0.17.
    const HemisphereFrame f(Vec3{0, 0, 1});
    Rng rng(42);
    const int k = 32;
    double c1 = 0, c2 = 0, x = 0, y = 0;
    for (int cell = 0; cell < k * k; ++cell) {
        const Vec3 d = cosineDirection(f, cell, k, rng);
        c1 += d.z;
        c2 += d.z * d.z;
        x += d.x;
        y += d.y;
    }
    const double n = k * k;
    EXPECT_NEAR(c1 / n, 2.0 / 3.0, 2e-3);
    EXPECT_NEAR(c2 / n, 0.5, 2e-3);
    EXPECT_NEAR(x / n, 0.0, 2e-3);
    EXPECT_NEAR(y / n, 0.0, 2e-3);
}

TEST(Parallel, EveryIndexOnceInLoopsAndChunks) {
    for (const size_t n : {size_t{0}, size_t{1}, size_t{1000}}) {
        std::vector<std::atomic<int>> seen(n);
        parallelFor(n, 7, [&](size_t i) { ++seen[i]; });
        std::vector<std::atomic<int>> chunked(n);
        std::atomic<int> badChunks{0};
        parallelForChunks(n, 16, [&](size_t first, size_t last) {
            if (!(first < last && last <= n)) ++badChunks;
            for (size_t i = first; i < last; ++i) ++chunked[i];
        });
        EXPECT_EQ(badChunks.load(), 0);
        for (size_t i = 0; i < n; ++i) {
            EXPECT_EQ(seen[i].load(), 1) << i;
            EXPECT_EQ(chunked[i].load(), 1) << i;
        }
    }
}

}  // namespace
}  // namespace radiosity
