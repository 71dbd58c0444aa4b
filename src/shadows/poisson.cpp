#include "shadows/poisson.h"

#include <cmath>
#include <random>

namespace penumbra {
namespace {

std::array<glm::vec2, kPoissonPoints> generate() {
    std::mt19937 rng(20261121u); // mt19937's sequence is fixed by the standard
    // Not std::uniform_real_distribution: its output is library-specific.
    auto uniform = [&] { return static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f); };
    auto inDisk = [&] {
        for (;;) {
            // Two statements: the order of a call's arguments is unspecified (gcc and clang
            // differ), and this order keeps the disk the tests were tuned with.
            const float y = 2.0f * uniform() - 1.0f;
            const glm::vec2 p(2.0f * uniform() - 1.0f, y);
            if (glm::dot(p, p) <= 1.0f)
                return p;
        }
    };
    std::array<glm::vec2, kPoissonPoints> points{};
    points[0] = inDisk();
    for (size_t n = 1; n < kPoissonPoints; ++n) {
        // Best of 16 n candidates: the one farthest from every point so far.
        float best = -1.0f;
        for (size_t c = 0; c < 16 * n; ++c) {
            const glm::vec2 candidate = inDisk();
            float nearest = 1e9f;
            for (size_t i = 0; i < n; ++i)
                nearest = std::min(nearest, glm::distance(candidate, points[i]));
            if (nearest > best)
                best = nearest, points[n] = candidate;
        }
    }
    return points;
}

} // namespace

const std::array<glm::vec2, kPoissonPoints>& poissonDisk() {
    static const std::array<glm::vec2, kPoissonPoints> points = generate();
    return points;
}

} // namespace penumbra
