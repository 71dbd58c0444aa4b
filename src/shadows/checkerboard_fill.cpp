// Checkerboard tracing's fill, transcribed from visibility_fill.comp.
#include "shadows/checkerboard_fill.h"

#include "shadows/visibility_filter.h"

#include "checkerboard.h"
#include "light_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::shadows {

float Checkerboard::rangeFor(uint32_t lightType, bool sized) const {
    if (!sized)
        return -1.0f;
    return lightType == LIGHT_POINT ? cubeRange : range;
}

CheckerboardFill fillCheckerboard(uint32_t width, uint32_t height, std::span<const float> position,
                                  std::span<const float> normal, std::span<const float> visibility,
                                  float range) {
    const size_t pixels = size_t{width} * height;
    CheckerboardFill out{
        .visibility = std::vector<float>(pixels, std::numeric_limits<float>::quiet_NaN()),
        .pixels = std::vector<CheckerboardPixel>(pixels, CheckerboardPixel::Background),
        .close = std::vector<bool>(pixels, false)};
    // Left, right, the row before, the row after: the shader's order.
    const glm::ivec2 steps[4] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t{y} * width + x;
            if (std::isnan(position[3 * i]))
                continue;
            if ((x + y) % 2 == 0) {
                out.pixels[i] = CheckerboardPixel::Traced;
                out.visibility[i] = visibility[i];
                continue;
            }
            const glm::vec3 p = pixelVector(position, i), n = pixelVector(normal, i);
            uint32_t count = 0;
            float lowest = 2.0f, highest = -1.0f, sum = 0.0f;
            for (const glm::ivec2 step : steps) {
                const std::optional<size_t> neighbour =
                    surfacePixel(width, height, position, static_cast<int>(x) + step.x,
                                 static_cast<int>(y) + step.y);
                if (!neighbour)
                    continue;
                const size_t j = *neighbour;
                const glm::vec3 q = pixelVector(position, j), m = pixelVector(normal, j);
                const glm::vec3 d = q - p;
                const float plane = std::abs(glm::dot(n, d)) - FILTER_PLANE_SLOPE * glm::length(d);
                const float facing = glm::dot(n, m) - FILTER_NORMAL_COS;
                if (std::abs(plane) <= 1e-4f * glm::length(d) || std::abs(facing) <= 1e-4f)
                    out.close[i] = true;
                lowest = std::min(lowest, visibility[j]);
                highest = std::max(highest, visibility[j]);
                if (!gpu::checkerboardSameSurface(p, n, q, m))
                    continue;
                sum += visibility[j];
                ++count;
            }
            if (gpu::checkerboardFills(count, lowest, highest, range)) {
                out.pixels[i] = CheckerboardPixel::Filled;
                out.visibility[i] = sum / static_cast<float>(count);
            } else {
                out.pixels[i] = CheckerboardPixel::Listed;
            }
        }
    return out;
}

} // namespace penumbra::shadows
