#pragma once
// What the translucent techniques' shadow maps keep in a texel, on the CPU: the texel's
// translucent surfaces (its ray's, from the light to the first opaque caster) reduced as the
// GPU's blending reduces them, and the transmittance a receiver reads back
// (shaders/include/translucent.h; docs/translucency.md, "Techniques"). Fed an ideal map's
// surfaces (EmbreeScene::surfacesAlong), they measure each technique's own approximation apart
// from the map's resolution.
#include <glm/glm.hpp>

#include <array>
#include <span>

namespace penumbra::shadows {

// A translucent surface on a texel's ray: its depth in [0, 1] (0 at the light's end) and what it
// lets through per channel.
struct TranslucentLayer {
    float depth;
    glm::vec3 transmittance;
};

// Coloured transmittance map: the nearest surface's depth (1 when there is none) and what it lets
// through (the first listed of those at that depth, as the depth test keeps the first drawn), the
// second nearest depth (the nearest past it; 1 when there is none) and the product of every
// surface's transmittance (multiplicative blending).
struct ColouredTexel {
    float nearest = 1.0f, second = 1.0f;
    glm::vec3 front{1.0f}, product{1.0f};
};
ColouredTexel colouredTexel(std::span<const TranslucentLayer> layers);
glm::vec3 colouredTransmittance(const ColouredTexel& texel, float depth);

// Moment-based transmittance: per channel, the sums of the surfaces' absorbances and of their
// absorbance-weighted depth moments (additive blending).
struct MomentTexel {
    glm::vec3 absorbance{0.0f};
    std::array<glm::vec4, 3> moments{}; // red, green, blue
};
MomentTexel momentTexel(std::span<const TranslucentLayer> layers);
glm::vec3 momentTransmittance(const MomentTexel& texel, float depth, float bias,
                              float overestimation);

// What the texel's surfaces in front of `depth` let through: the truth the two approximate.
glm::vec3 exactTransmittance(std::span<const TranslucentLayer> layers, float depth);

} // namespace penumbra::shadows
