// Layer `translucent`: light through translucent casters (docs/translucency.md). The light's
// depth map leaves the translucent casters out; the frame draws them from the light into maps of
// their own, by the method translucent.method names, and this layer's pass
// (shaders/translucent.comp) multiplies each light's visibility by what they let through at the
// pixel. Two methods, both order-independent (blending):
// - a coloured transmittance map: the product of the surfaces' transmittances, the nearest
//   surface's and the two nearest depths (engines' translucent shadow maps keep the product and
//   the nearest depth; the second depth makes a receiver under one surface exact);
// - moment-based transmittance [Muenstermann et al. 2018, 'Moment-based order-independent
//   transparency', with its shadows for translucent casters]: per channel, the absorbance and its
//   four power moments of depth.
// Their texels and reads are shaders/include/translucent.h, shared with the CPU reference
// (src/shadows/translucent_maps.h). Every light type; every base technique that draws a depth
// map (not virtual maps yet).
#include "translucent.h"
#include "shadows/layer.h"

#include <iterator>

namespace penumbra::shadows {

gpu::TranslucentParams translucentParams(const ParameterValues& p) {
    return {.method = {static_cast<uint32_t>(p.number("translucent.method")), 0u, 0u, 0u},
            .moments = {TRANSLUCENT_MOMENT_BIAS,
                        static_cast<float>(p.number("translucent.overestimation")), 0.0f, 0.0f}};
}

const LayerModule& translucentLayer() {
    static const char* const methods[] = {"off", "coloured", "moments"};
    static_assert(TRANSLUCENT_OFF == 0 && TRANSLUCENT_COLOURED == 1 && TRANSLUCENT_MOMENTS == 2 &&
                  std::size(methods) == 3);
    static const LayerModule layer{
        .name = "translucent",
        .summary = "light through translucent casters (glTF BLEND, KHR_materials_transmission): "
                   "their maps drawn from the light beside the depth map, each light's "
                   "visibility multiplied by what they let through",
        .reference = "coloured transmittance maps, as engines' translucent shadow maps; "
                     "Muenstermann et al. 2018, 'Moment-based order-independent transparency'",
        .parameters = {{.key = "translucent.method",
                        .type = ParameterType::Choice,
                        .defaultValue = TRANSLUCENT_OFF,
                        .choices = {std::begin(methods), std::end(methods)},
                        .description =
                            "how the translucent casters' shadows are kept: not at all, they "
                            "cast opaque ones (`off`: the layer does not run); the product of "
                            "their transmittances, the nearest one's and the two nearest depths "
                            "(`coloured`); "
                            "their absorbances' moments per channel (`moments`). On a scene "
                            "without translucent casters the layer does not run"},
                       {.key = "translucent.overestimation",
                        .type = ParameterType::Float,
                        .defaultValue = 0.0,
                        .min = 0.0,
                        .max = 1.0,
                        .description =
                            "translucent.method=moments: how far each channel's share of the "
                            "absorbance in front of a receiver moves from the moments' lower "
                            "bound towards their upper one (0: the lower bound; any share "
                            "measured worse on builtin:sheets)"}},
        .enabled = [](const ParameterValues& p) { return p.number("translucent.method") > 0.0; },
        .off = {"translucent.method", "off"},
        .shader = "translucent.comp",
        .pack = [](const ParameterValues& p,
                   ParamBlock& block) { block.set(translucentParams(p)); },
        .rowSettings =
            [](double) {
                // Measured (docs/translucency.md, "Which method"): as close as the moments on
                // builtin:sheets, closer on builtin:tree, in 24 bytes a texel against 64.
                return std::vector<std::pair<std::string, std::string>>{
                    {"translucent.method", "coloured"}};
            },
        .rows = {},
        .translucentMethod =
            [](const ParameterValues& p) {
                return static_cast<uint32_t>(p.number("translucent.method"));
            }};
    return layer;
}

} // namespace penumbra::shadows
