#pragma once
// A synthetic G-buffer for the ground truth's CPU tests: `size` x `size` pixels on the plane
// y = 0 around (cx, cz), `extent` wide, facing up.
#include "penumbra/renderer.h"

#include <cstdint>

namespace penumbra::test {

inline RenderResult planeGrid(float cx, float cz, float extent, uint32_t size = 128) {
    RenderResult g{.width = size, .height = size};
    const auto n = static_cast<float>(size);
    g.position.resize(3 * size_t{size} * size);
    g.normal.resize(3 * size_t{size} * size);
    for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
            const size_t i = size_t{y} * size + x;
            g.position[3 * i] = cx + extent * ((static_cast<float>(x) + 0.5f) / n - 0.5f);
            g.position[3 * i + 2] = cz + extent * ((static_cast<float>(y) + 0.5f) / n - 0.5f);
            g.normal[3 * i + 1] = 1.0f;
        }
    return g;
}

} // namespace penumbra::test
