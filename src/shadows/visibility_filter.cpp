// The edge-aware visibility filter's CPU mirror: visibility_filter.comp's two passes transcribed.
#include "shadows/visibility_filter.h"

#include "light_geometry.h"
#include "visibility_filter_weights.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {
namespace {

// One pass along `axis` (0 rows, 1 columns), as one dispatch of the shader.
std::vector<float> filterPass(uint32_t width, uint32_t height, std::span<const float> position,
                              std::span<const float> normal, std::span<const float> source,
                              VisibilityFilter filter, int axis) {
    std::vector<float> out(source.begin(), source.end());
    const int radius = static_cast<int>(filter.radius);
    const int wide = radius > 0 ? static_cast<int>(filter.wide) : 0; // as wideFor
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            const size_t i = size_t{y} * width + x;
            if (std::isnan(position[3 * i]))
                continue; // background
            // How far the pixel reaches: as far as its neighbours stay in a penumbra on both sides,
            // up to `wide`, where it is in one.
            int reach = radius;
            if (wide > radius && gpu::visibilityFilterInPenumbra(source[i])) {
                int run = wide;
                for (int side = -1; side <= 1; side += 2)
                    for (int o = 1; o <= wide; ++o) {
                        const int qx = static_cast<int>(x) + (axis == 0 ? side * o : 0);
                        const int qy = static_cast<int>(y) + (axis == 1 ? side * o : 0);
                        const bool onImage = qx >= 0 && qy >= 0 && qx < static_cast<int>(width) &&
                                             qy < static_cast<int>(height);
                        const size_t j =
                            onImage ? static_cast<size_t>(qy) * width + static_cast<size_t>(qx) : 0;
                        if (!onImage || std::isnan(position[3 * j]) ||
                            !gpu::visibilityFilterInPenumbra(source[j])) {
                            run = std::min(run, o - 1);
                            break;
                        }
                    }
                reach = std::max(radius, run);
            }
            float weights = 0.0f, sum = 0.0f;
            for (int offset = -reach; offset <= reach; ++offset) {
                const std::optional<size_t> q = surfacePixel(
                    width, height, position, static_cast<int>(x) + (axis == 0 ? offset : 0),
                    static_cast<int>(y) + (axis == 1 ? offset : 0));
                if (!q)
                    continue;
                const size_t j = *q;
                const float w = gpu::visibilityFilterWeight(
                    pixelVector(position, i), pixelVector(normal, i), source[i],
                    pixelVector(position, j), pixelVector(normal, j), source[j], offset, reach,
                    filter.tolerance);
                weights += w;
                sum += w * source[j];
            }
            out[i] = std::clamp(sum / weights, 0.0f, 1.0f);
        }
    return out;
}

} // namespace

std::optional<size_t> surfacePixel(uint32_t width, uint32_t height, std::span<const float> position,
                                   int x, int y) {
    if (x < 0 || y < 0 || x >= static_cast<int>(width) || y >= static_cast<int>(height))
        return std::nullopt;
    const size_t i = static_cast<size_t>(y) * width + static_cast<size_t>(x);
    if (std::isnan(position[3 * i]))
        return std::nullopt;
    return i;
}

uint32_t VisibilityFilter::radiusFor(uint32_t lightType) const {
    return lightType == LIGHT_POINT ? cubeRadius : radius;
}

float VisibilityFilter::toleranceFor(uint32_t lightType) const {
    return lightType == LIGHT_POINT ? cubeTolerance : tolerance;
}

uint32_t VisibilityFilter::wideFor(uint32_t lightType) const {
    const uint32_t r = radiusFor(lightType);
    return r > 0 ? std::max(r, lightType == LIGHT_POINT ? cubeWide : wide) : 0;
}

std::vector<float> filterVisibility(uint32_t width, uint32_t height,
                                    std::span<const float> position, std::span<const float> normal,
                                    std::span<const float> visibility, VisibilityFilter filter) {
    const std::vector<float> rows =
        filterPass(width, height, position, normal, visibility, filter, 0);
    return filterPass(width, height, position, normal, rows, filter, 1);
}

} // namespace penumbra::shadows
