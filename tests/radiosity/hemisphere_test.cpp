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

TEST(Hemisphere, AStrataWindowHoldsEveryRayThatMeetsItsBall) {
    // StrataWindow bounds where, in the strata's square, the rays toward a ball may lie; a
    // gather skips the ball on the other strata, so a ray that meets the ball outside its
    // window would be lost. Many random directions (64 jittered draws in each of 32 x 32
    // strata) from random normals toward balls of random size and place, near (the ball
    // filling much of the hemisphere) and far, on the horizon and behind it: each ray that
    // meets the ball must lie in a stratum the window holds. And the window must be useful:
    // for small far balls it holds a small share of the strata.
    Rng rng(2026);
    const int k = 32;
    size_t met = 0;
    double heldSmall = 0;
    int small = 0;
    for (int trial = 0; trial < 400; ++trial) {
        const Vec3 n =
            glm::normalize(Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5});
        const HemisphereFrame f(n);
        const Vec3 centre =
            3.0 * Vec3{rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5} + 0.3 * n;
        const double r = 0.02 + 0.5 * rng.uniform() * rng.uniform();
        const StrataWindow w = StrataWindow::toward(f, Vec3{0, 0, 0}, centre, r);
        int held = 0;
        for (int cell = 0; cell < k * k; ++cell) {
            held += w.mayHold(cell, k) ? 1 : 0;
            for (int draw = 0; draw < 64; ++draw) {
                const Vec3 d = cosineDirection(f, cell, k, rng);
                // Does the ray t d (t > 0) meet the ball?
                const double along = glm::dot(centre, d);
                const double miss = glm::length(centre - along * d);
                if (!(along > 0 && miss <= r)) continue;
                ++met;
                ASSERT_TRUE(w.mayHold(cell, k))
                    << "trial " << trial << " cell " << cell << ": a ray meets the ball";
            }
        }
        if (!w.everywhere() && r / glm::length(centre) < 0.05) {
            heldSmall += static_cast<double>(held) / (k * k);
            ++small;
        }
    }
    EXPECT_GT(met, 10000u) << "too few rays met the balls to test the bound";
    ASSERT_GT(small, 10);
    EXPECT_LT(heldSmall / small, 0.05) << "the windows of small far balls hold too much";
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
