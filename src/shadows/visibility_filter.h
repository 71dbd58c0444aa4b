#pragma once
// The CPU mirror of the edge-aware visibility filter (shaders/visibility_filter.comp, its weights
// in shaders/include/visibility_filter_weights.h): the parity test runs it on a render's own
// exported positions, normals and unfiltered visibility.
#include "shadows/technique.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace penumbra::shadows {

// What the filter and checkerboard tracing's fill (checkerboard_fill.h) read of a pixel: its
// index when (x, y) lies on the image and on a surface (position not NaN), and an xyz vector.
std::optional<size_t> surfacePixel(uint32_t width, uint32_t height, std::span<const float> position,
                                   int x, int y);
inline glm::vec3 pixelVector(std::span<const float> v, size_t i) {
    return {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
}

// One visibility layer, filtered along rows and then columns. position and normal: xyz per
// pixel, NaN for the background (whose visibility is passed through).
std::vector<float> filterVisibility(uint32_t width, uint32_t height,
                                    std::span<const float> position, std::span<const float> normal,
                                    std::span<const float> visibility, VisibilityFilter filter);

} // namespace penumbra::shadows
