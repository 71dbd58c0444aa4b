// Layer `temporal`: a light's visibility accumulated over frames, as engines amortise soft
// shadows [Karis 2014, "High-quality temporal supersampling"; Salvi 2016, "An excursion in
// temporal supersampling" (variance clipping); Schied et al. 2017, "Spatiotemporal
// variance-guided filtering" (reprojection through motion vectors, disocclusion from depth and
// normal)]. Each frame the techniques turn their per-pixel rotations (frameTurn: pcf's and pcss's
// Poisson disks, smrt's rays, contact's jitter), so that their few samples a frame differ from
// the last frame's; the layer reprojects the pixel's history through the G-buffer's motion
// vectors, keeps the texels that show the same surface and that this frame does not contradict
// (the reset rule: each texel's spread over time and the neighbourhoods' means), clamps what
// they say into the range this frame's neighbourhood allows and blends this frame in with weight
// 1/n (n frames so far, at most temporal.frames). Shader: shaders/temporal.comp; maths:
// shaders/include/temporal.h.
#include "temporal.h"
#include "shadows/layer.h"

#include <iterator>

namespace penumbra::shadows {
namespace {

gpu::TemporalParams temporalParams(const ParameterValues& p) {
    return {.frames = static_cast<uint32_t>(p.number("temporal.frames")),
            .clampMode = static_cast<uint32_t>(p.number("temporal.clamp")),
            .gamma = static_cast<float>(p.number("temporal.gamma")),
            .depthTolerance = static_cast<float>(p.number("temporal.depthTolerance")),
            .normalTolerance = static_cast<float>(p.number("temporal.normalTolerance")),
            .reset = static_cast<float>(p.number("temporal.reset"))};
}

} // namespace

const LayerModule& temporalLayer() {
    static const char* const clampChoices[] = {"none", "minmax", "variance"};
    static_assert(TEMPORAL_CLAMP_NONE == 0 && TEMPORAL_CLAMP_MINMAX == 1 &&
                  TEMPORAL_CLAMP_VARIANCE == 2 && std::size(clampChoices) == 3);
    static const LayerModule layer{
        .name = "temporal",
        .summary = "the light's visibility averaged over frames: history reprojected through "
                   "motion vectors, dropped where the surface changed or this frame contradicts "
                   "it, clamped to this frame's neighbourhood; the techniques turn their samples "
                   "every frame",
        .reference = "Karis 2014, 'High-quality temporal supersampling'; Salvi 2016, 'An "
                     "excursion in temporal supersampling'; Schied et al. 2017, "
                     "'Spatiotemporal variance-guided filtering'",
        .parameters =
            {{.key = "temporal.frames",
              .type = ParameterType::Int,
              .defaultValue = 0,
              .min = 0,
              .max = 256,
              .unit = "frames",
              .description = "the longest history averaged: each frame weighs 1/n of the n "
                             "frames so far, at least 1/temporal.frames (0: off, the layer does "
                             "not run)"},
             {.key = "temporal.clamp",
              .type = ParameterType::Choice,
              .defaultValue = TEMPORAL_CLAMP_MINMAX,
              .choices = {std::begin(clampChoices), std::end(clampChoices)},
              .description = "what bounds the history: nothing (`none`), this frame's 3x3 "
                             "neighbourhood's smallest and largest visibility (`minmax`), or its "
                             "mean +- temporal.gamma deviations (`variance`)"},
             {.key = "temporal.gamma",
              .type = ParameterType::Float,
              .defaultValue = 1.0,
              .min = 0.0,
              .max = 16.0,
              .unit = "deviations",
              .description = "temporal.clamp=variance: the range's half-width"},
             {.key = "temporal.depthTolerance",
              .type = ParameterType::Float,
              .defaultValue = 0.02,
              .min = 0.0,
              .max = 1.0,
              .description = "a history texel shows the pixel's surface when its depth differs "
                             "from where the surface was by at most this fraction (NDC depth: "
                             "the relative distance for a perspective camera) ..."},
             {.key = "temporal.normalTolerance",
              .type = ParameterType::Float,
              .defaultValue = 0.9,
              .min = -1.0,
              .max = 1.0,
              .description = "... and the cosine between their triangles' normals is at least "
                             "this"},
             {.key = "temporal.reset",
              .type = ParameterType::Float,
              .defaultValue = 2.0,
              .min = 0.0,
              .max = 16.0,
              .unit = "deviations",
              .description = "the reset rule's k: a history texel is dropped where this frame's "
                             "visibility leaves its mean by more than k of its deviations over "
                             "time (pooled with the 3x3 neighbourhood's variance), a pixel's "
                             "history where the neighbourhood's mean leaves the history's there "
                             "by more than k deviations over the root of their places (pooled "
                             "with the residuals' variance); changes under 1/512 never: a moving "
                             "shadow does not trail (0: off)"}},
        .enabled = [](const ParameterValues& p) { return p.number("temporal.frames") > 0.0; },
        .off = {"temporal.frames", "0"},
        .shader = "temporal.comp",
        .pack = [](const ParameterValues& p, ParamBlock& block) { block.set(temporalParams(p)); },
        .rowSettings =
            [](double) {
                return std::vector<std::pair<std::string, std::string>>{{"temporal.frames", "16"}};
            },
        .rows = {},
        .history = MapFormat::RGBA32UI,
        .warmUpFrames =
            [](const ParameterValues& p) {
                return static_cast<uint32_t>(p.number("temporal.frames"));
            }};
    return layer;
}

} // namespace penumbra::shadows
