// Technique `hard` [Williams 1978]: one nearest-texel sample of the light's depth map; lit when
// d(p) <= s(p). Shader: shaders/include/shadow_hard.glsl. Parameters: the `bias` family only.
#include "shadows/technique.h"

namespace penumbra::shadows {

const TechniqueModule& hardModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Hard,
                 .name = "hard",
                 .summary = "one shadow-map sample per pixel: lit when d(p) <= s(p)",
                 .reference = "Williams 1978, 'Casting curved shadows on curved surfaces'",
                 .families = {"bias", "csm", "composite"},
                 .variants = {{.label = ""}}},
        .blurRadiusTexels = [](const ParameterValues&) { return 0.5; }};
    return module;
}

} // namespace penumbra::shadows
