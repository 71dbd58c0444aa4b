// Technique `pcss` [Fernando 2005]: a blocker search over the light's extent, a penumbra
// estimate from similar triangles, then Poisson PCF of that width (contact hardening). Shader:
// shaders/include/shadow_pcss.glsl, its block shaders/include/params_pcf.h; CPU mirror:
// pcssReference below; derivations in docs/techniques.md. Its kernels follow the light's size,
// capped at pcss.maxRadius texels: a blocker-searching module (searchCap), whose search and
// filter the visibility pass may run in different cascades of a sun.
#include "light_geometry.h"
#include "params_pcf.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_filters.h"
#include "shadows/technique.h"

#include <algorithm>

namespace penumbra::shadows {
namespace {

// searchBlockers, transcribed: how many of the 4 n texels block, and their average depth.
float searchBlockers(const FilterInput& in, const CpuReceiver& r, uint32_t n, float radius,
                     float turns, glm::vec2 dzRange, float& averageDepth) {
    const ShadowMapView& map = in.map;
    const float size = static_cast<float>(map.size);
    const glm::vec2 centre = r.uv * size;
    float sum = 0.0f, count = 0.0f;
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec2 p =
            centre + gpu::rotatedOffset(poissonPoint(in.frame, i), turns, radius) - 0.5f;
        const glm::ivec2 base = glm::ivec2(glm::floor(p));
        const glm::vec4 depths(map.texel(base.x, base.y + 1), map.texel(base.x + 1, base.y + 1),
                               map.texel(base.x + 1, base.y), map.texel(base.x, base.y));
        const glm::vec4 blocks =
            glm::vec4(1.0f) - gatherTests(map, base, size, r, dzRange, in.margins);
        sum += glm::dot(blocks, depths);
        count += blocks.x + blocks.y + blocks.z + blocks.w;
    }
    averageDepth = count > 0.0f ? sum / count : 1.0f;
    return count;
}

// shadowPcssDetail: x visibility, y average blocker depth, z blocking texels, w filter radius.
glm::vec4 pcssReference(const FilterInput& in) {
    const gpu::PcssParams p = in.params.get<gpu::PcssParams>();
    const gpu::ShadowViewData& view = in.view;
    const uint32_t mapSize = in.map.size;
    const CpuReceiver r = receiverOf(in.probe);
    const glm::vec2 dzRange(in.frame.biasParams.x, in.frame.biasParams.y);
    const float turns = gpu::rotationTurns(p.rotation, in.probe.pixel);
    const float zReceiver = gpu::viewDistance(view, r.depth);
    const float cap = gpu::kernelCap(view, p.maxRadius, p.cubeRadius);
    const float search = std::min(gpu::blockerSearchRadius(view, zReceiver, mapSize), cap);
    float blockerDepth = 1.0f;
    const float blockers = searchBlockers(in, r, p.blockerSamples, std::max(search, 0.5f), turns,
                                          dzRange, blockerDepth);
    if (blockers == 0.0f)
        return {1.0f, blockerDepth, 0.0f, 0.0f};
    const float zBlocker = gpu::viewDistance(view, blockerDepth);
    const float radius =
        std::clamp(gpu::penumbraRadius(view, zReceiver, zBlocker, mapSize), 0.5f, cap);
    if (blockers == 4.0f * static_cast<float>(p.blockerSamples) && radius <= 1.0f)
        return {0.0f, blockerDepth, blockers, radius};
    const float v =
        poissonTaps(in.map, r, in.frame, p.filterSamples, radius, turns, dzRange, in.margins);
    return {gpu::snapToExtremes(v), blockerDepth, blockers, radius};
}

} // namespace

const TechniqueModule& pcssModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Pcss,
                 .name = "pcss",
                 .summary =
                     "percentage-closer soft shadows: blocker search, penumbra estimate, PCF of "
                     "that width (contact hardening)",
                 .reference = "Fernando 2005, 'Percentage-closer soft shadows'",
                 .families = {"bias", "pcss", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "fast",
                               .sets = {{"pcss.blockerSamples", "8"},
                                        {"pcss.filterSamples", "16"}}}}},
        .parameters =
            {{.key = "pcss.blockerSamples",
              .type = ParameterType::Int,
              .defaultValue = 24,
              .min = 1,
              .max = 64,
              .unit = "gathers (4 texels each)",
              .description = "blocker-search taps on a Poisson disk over the search region"},
             {.key = "pcss.filterSamples",
              .type = ParameterType::Int,
              .defaultValue = 48,
              .min = 1,
              .max = 64,
              .description = "PCF taps (bilinear, Poisson disk) over the estimated penumbra"},
             {.key = "pcss.maxRadius",
              .type = ParameterType::Float,
              .defaultValue = 40.0,
              .min = 1.0,
              .max = 256.0,
              .unit = "texels",
              .description = "largest blocker-search and filter radius, in texels of the map "
                             "sampled on spots and a sun's cascades (a sun's PCSS moves to a "
                             "coarser cascade rather than clip)"},
             cubeRadiusParameter("pcss.cubeRadius"),
             {.key = "pcss.rotation",
              .type = ParameterType::Choice,
              .defaultValue = 2,
              .choices = {std::begin(gpu::kRotationChoices), std::end(gpu::kRotationChoices)},
              .description = "per-pixel rotation of both Poisson disks"}},
        // Its search and filter may fall in different cascades of a sun (STAGE_SEARCH,
        // STAGE_FILTER), capped at pcss.maxRadius texels (blockerSearchKey).
        .constants =
            [](const ParameterValues&) {
                return std::vector<SpecConstant>{{SPEC_BLOCKER_SEARCH, 1u}};
            },
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                auto choice = [&](const char* key) { return static_cast<uint32_t>(p.number(key)); };
                block.set(
                    gpu::PcssParams{.blockerSamples = choice("pcss.blockerSamples"),
                                    .filterSamples = choice("pcss.filterSamples"),
                                    .rotation = choice("pcss.rotation"),
                                    .maxRadius = static_cast<float>(p.number("pcss.maxRadius")),
                                    .cubeRadius = static_cast<float>(p.number("pcss.cubeRadius"))});
            },
        .reference = pcssReference,
        .modelsLightSize = true,
        .blurRadiusTexels =
            [](const ParameterValues& p) { return p.number("pcss.maxRadius") + 1.0; },
        .cubeRadiusTexels =
            [](const ParameterValues& p) { return p.number("pcss.cubeRadius") + 1.0; },
        .blockerSearchKey = "pcss.maxRadius",
        .readsVirtualMaps = true};
    return module;
}

} // namespace penumbra::shadows
