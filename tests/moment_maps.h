#pragma once
// Synthetic shadow maps and receivers for the prefiltered family's probe tests (test_moments.cpp,
// test_soft_moments.cpp): a smooth receiver under boxes, a step between two depths, two lights.
#include "penumbra/renderer.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace penumbra::test {

inline constexpr uint32_t kSize = 64;

// A smooth receiver with box-shaped occluders nearer the light.
inline std::vector<float> boxesOverAWave(uint32_t seed) {
    std::mt19937 engine(seed);
    auto rng = [&] { return static_cast<uint32_t>(engine()); };
    std::vector<float> depth(kSize * kSize);
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
            depth[j * kSize + i] =
                0.6f + 0.1f * std::sin(0.3f * float(i)) * std::cos(0.2f * float(j));
    for (int b = 0; b < 14; ++b) {
        const uint32_t x0 = rng() % kSize, y0 = rng() % kSize, w = 2 + rng() % 10,
                       h = 2 + rng() % 10;
        const float d = 0.2f + 0.3f * float(rng() % 1000) / 1000.0f;
        for (uint32_t y = y0; y < std::min(y0 + h, kSize); ++y)
            for (uint32_t x = x0; x < std::min(x0 + w, kSize); ++x)
                depth[y * kSize + x] = d;
    }
    return depth;
}

inline std::vector<FilterProbe> probesOver(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<FilterProbe> probes(1500);
    for (FilterProbe& p : probes) {
        p.uv = {unit(rng), unit(rng)}; // the whole map, edges included (clamp-to-edge)
        p.depth = 0.15f + 0.7f * unit(rng);
    }
    return probes;
}

inline const ProbeLight kLights[] = {
    {.perspective = false, .nearPlane = 1.0f, .farPlane = 21.0f, .worldPerUv = {12.0f, 12.0f}},
    {.perspective = true, .nearPlane = 0.5f, .farPlane = 30.0f, .worldPerUv = {1.2f, 1.2f}}};

// Depth a left of the middle, b right of it: across the middle, bilinear interpolation mixes two
// atoms, a with weight 1 - s and b with weight s, s the way from texel 31's centre to 32's.
inline std::vector<float> stepMap(float a, float b) {
    std::vector<float> depth(kSize * kSize);
    for (uint32_t j = 0; j < kSize; ++j)
        for (uint32_t i = 0; i < kSize; ++i)
            depth[j * kSize + i] = i < kSize / 2 ? a : b;
    return depth;
}

// A probe at receiver depth t, the way s across the step.
inline FilterProbe acrossTheStep(double s, float t) {
    return {.uv = {static_cast<float>((31.5 + s) / kSize), 0.5f}, .depth = t};
}

} // namespace penumbra::test
