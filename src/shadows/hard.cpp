// Technique `hard` [Williams 1978]: one nearest-texel sample of the light's depth map; lit when
// d(p) <= s(p). Shader: shaders/include/shadow_hard.glsl. Parameters: the `bias` family only.
#include "shadows/cpu_filters.h"
#include "shadows/technique.h"

namespace penumbra::shadows {

const TechniqueModule& hardModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Hard,
                 .name = "hard",
                 .summary = "one shadow-map sample per pixel: lit when d(p) <= s(p)",
                 .reference = "Williams 1978, 'Casting curved shadows on curved surfaces'",
                 .families = {"bias", "csm", "composite"}},
        .reference =
            [](const FilterInput& in) {
                const glm::vec2 dzRange(in.frame.biasParams.x, in.frame.biasParams.y);
                return glm::vec4(hardTest(in.map, in.probe, in.margins, dzRange), 0.0f, 0.0f, 0.0f);
            },
        .blurRadiusTexels = [](const ParameterValues&) { return 0.5; },
        .readsVirtualMaps = true};
    return module;
}

} // namespace penumbra::shadows
