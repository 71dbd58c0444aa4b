// Technique `second-depth` [Wang and Molnar 1994]: a depth peel keeps the second-nearest caster
// per texel, a post pass stores the midpoint of the two layers, and the visibility pass tests
// against it with the hard technique's one sample: a surface never shadows itself, with no bias,
// as long as the geometry is watertight (shaders/shadow_peel.frag, second_depth_mid.comp,
// shaders/include/shadow_second_depth.glsl).
#include "shadows/cpu_filters.h"
#include "shadows/technique.h"

namespace penumbra::shadows {

const TechniqueModule& secondDepthModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::SecondDepth,
                 .name = "second-depth",
                 .summary =
                     "one sample against the midpoint of the nearest and second-nearest depths: "
                     "no self-shadowing without bias, for watertight geometry",
                 .reference = "Wang and Molnar 1994, 'Second-depth shadow mapping'",
                 .families = {"bias", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "nobias", // the paper's claim: no bias at all
                               .sets = {{"bias.mode", "fixed"},
                                        {"bias.constant", "0"},
                                        {"bias.slope", "0"},
                                        {"bias.normal", "0"},
                                        {"bias.receiver", "off"}}}}},
        .maps = {{.name = "second", .format = MapFormat::Depth32},
                 {.name = "midpoint", .format = MapFormat::R32F}},
        .depthPasses = {{.target = "second",
                         .fragmentShader = "shadow_peel.frag",
                         .reads = kDepthMap}},
        .postPasses = {{.shader = "second_depth_mid.comp",
                        .inputs = {kDepthMap, "second"},
                        .outputs = {"midpoint"}}},
        .visibilityMaps = {"midpoint"},
        // The probe's map holds the midpoints; no receiver-plane correction.
        .reference =
            [](const FilterInput& in) {
                return glm::vec4(hardTest(in.map, in.probe, in.margins, glm::vec2(0.0f)), 0.0f,
                                 0.0f, 0.0f);
            },
        .blurRadiusTexels = [](const ParameterValues&) { return 0.5; },
        .needsClosedSurfaces = true};
    return module;
}

} // namespace penumbra::shadows
