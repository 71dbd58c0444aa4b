#include "shadows/translucent_maps.h"

#include "translucent.h"

#include <algorithm>

namespace penumbra::shadows {

ColouredTexel colouredTexel(std::span<const TranslucentLayer> layers) {
    ColouredTexel texel;
    for (const TranslucentLayer& layer : layers) {
        if (layer.depth < texel.nearest) {
            texel.nearest = layer.depth;
            texel.front = layer.transmittance;
        }
        texel.product *= layer.transmittance;
    }
    for (const TranslucentLayer& layer : layers)
        if (layer.depth > texel.nearest)
            texel.second = std::min(texel.second, layer.depth);
    return texel;
}

glm::vec3 colouredTransmittance(const ColouredTexel& texel, float depth) {
    return gpu::colouredMapTransmittance(texel.front, texel.product, texel.nearest, texel.second,
                                         depth);
}

MomentTexel momentTexel(std::span<const TranslucentLayer> layers) {
    MomentTexel texel;
    for (const TranslucentLayer& layer : layers) {
        const glm::vec3 absorbance = gpu::layerAbsorbance(layer.transmittance);
        texel.absorbance += absorbance;
        for (int c = 0; c < 3; ++c)
            texel.moments[size_t(c)] += gpu::layerMoments(absorbance[c], layer.depth);
    }
    return texel;
}

glm::vec3 momentTransmittance(const MomentTexel& texel, float depth, float bias,
                              float overestimation) {
    glm::vec3 through;
    for (int c = 0; c < 3; ++c)
        through[c] = gpu::momentTransmittance(texel.absorbance[c], texel.moments[size_t(c)], depth,
                                              bias, overestimation);
    return through;
}

glm::vec3 exactTransmittance(std::span<const TranslucentLayer> layers, float depth) {
    glm::vec3 through(1.0f);
    for (const TranslucentLayer& layer : layers)
        if (layer.depth < depth)
            through *= layer.transmittance;
    return through;
}

} // namespace penumbra::shadows
