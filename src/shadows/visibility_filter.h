#pragma once
// The CPU mirror of the edge-aware visibility filter (shaders/visibility_filter.comp, its weights
// in shaders/include/visibility_filter_weights.h): the parity test runs it on a render's own
// exported positions, normals and unfiltered visibility.
#include "shadows/technique.h"

#include <cstdint>
#include <span>
#include <vector>

namespace penumbra::shadows {

// One visibility layer, filtered along rows and then columns. position and normal: xyz per
// pixel, NaN for the background (whose visibility is passed through).
std::vector<float> filterVisibility(uint32_t width, uint32_t height,
                                    std::span<const float> position, std::span<const float> normal,
                                    std::span<const float> visibility, VisibilityFilter filter);

} // namespace penumbra::shadows
