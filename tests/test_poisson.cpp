// The Poisson disk behind Poisson PCF and PCSS: Mitchell's best-candidate points are progressive,
// so every prefix pcf.samples = k takes is itself spread over the disk.
#include "shadows/poisson.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace penumbra;

namespace {

double minimumDistance(size_t n) {
    const auto& disk = poissonDisk();
    double best = 1e9;
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            best = std::min(best, double(glm::distance(disk[i], disk[j])));
    return best;
}

} // namespace

TEST(PoissonDisk, EveryPointLiesInTheUnitDiskAndNoTwoCoincide) {
    const auto& disk = poissonDisk();
    ASSERT_EQ(disk.size(), 64u);
    for (const glm::vec2& p : disk)
        EXPECT_LE(glm::length(p), 1.0f);
    EXPECT_GT(minimumDistance(64), 0.0);
}

TEST(PoissonDisk, EveryPrefixIsWellSpread) {
    // n points in a unit disk packed as densely as discs can be sit about sqrt(2 pi / (sqrt(3)
    // n)) apart; best-candidate sampling reaches over 70% of that. Uniform random points
    // would come much closer (their nearest pair shrinks like 1/n).
    const auto& disk = poissonDisk();
    for (size_t n : {4u, 8u, 16u, 24u, 32u, 48u, 64u}) {
        const double packed = std::sqrt(2.0 * M_PI / (std::sqrt(3.0) * double(n)));
        const double d = minimumDistance(n);
        std::printf("first %zu points: nearest pair %.3f, hexagonal packing %.3f\n", n, d, packed);
        EXPECT_GT(d, 0.7 * packed) << "first " << n << " points";
        // Balanced: the centroid stays near the centre, and every quadrant and ring gets points.
        glm::dvec2 centroid(0.0);
        size_t quadrant[4] = {}, inner = 0;
        for (size_t i = 0; i < n; ++i) {
            centroid += glm::dvec2(disk[i]);
            ++quadrant[(disk[i].x >= 0 ? 1 : 0) + (disk[i].y >= 0 ? 2 : 0)];
            inner += glm::length(disk[i]) < std::sqrt(0.5f); // half the disk's area
        }
        EXPECT_LT(glm::length(centroid / double(n)), 0.75 / std::sqrt(double(n)))
            << "first " << n << " points";
        for (size_t q : quadrant)
            EXPECT_GE(q, n / 8) << "first " << n << " points";
        EXPECT_GE(inner, n / 4) << "first " << n << " points";
        EXPECT_LE(inner, 3 * n / 4) << "first " << n << " points";
    }
}
