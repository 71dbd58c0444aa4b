// Technique `vsm` [Donnelly and Lauritzen 2006, 'Variance shadow maps']: two post passes take the
// moments (z, z^2) of the light's depth and blur them with a separable Gaussian
// (shaders/include/moments_blur.glsl); the visibility pass interpolates them bilinearly and
// bounds the lit fraction by Chebyshev's inequality, with a minimum variance and light-bleeding
// reduction [Lauritzen 2007] (shaders/include/shadow_moments.glsl). vsm.filter=mip adds the
// paper's mip chain over the blurred moments (vsm_mip.comp), read trilinearly over the pixel's
// footprint with up to vsm.anisotropy taps along its longer axis. CPU mirror:
// vsmReference below (src/shadows/cpu_moments.cpp: the blur and the chain); derivations in
// docs/techniques.md. Its block: shaders/include/params_moments.h.
#include "moments.h"
#include "params_moments.h"
#include "penumbra/renderer.h"
#include "shadows/cpu_moments.h"
#include "shadows/technique.h"

namespace penumbra::shadows {
namespace {

constexpr GaussianBlur kBlur{.sizeKey = "vsm.size",
                             .rowsShader = "vsm_blur_rows.comp",
                             .columnsShader = "vsm_blur_columns.comp",
                             .output = "moments",
                             .format = MapFormat::RG32F};

constexpr double kFilterMip = 1.0; // vsm.filter's second choice

bool filtersThroughMips(const ParameterValues& p) {
    return p.number("vsm.filter") == kFilterMip;
}

std::vector<MapDecl> vsmMaps() {
    std::vector<MapDecl> maps = kBlur.maps();
    for (MapDecl& map : maps)
        if (map.name == kBlur.output)
            map.mipmappedFor = filtersThroughMips;
    return maps;
}

std::vector<PostPassDecl> vsmPasses() {
    std::vector<PostPassDecl> passes = kBlur.passes();
    passes.push_back(
        {.shader = "vsm_mip.comp", .outputs = {kBlur.output}, .dispatch = PostDispatch::MipChain});
    return passes;
}

// shadowVsmDetail: x visibility, yz the filtered moments, w the receiver's moment depth.
glm::vec4 vsmReference(const FilterInput& in) {
    const gpu::VsmParams p = in.params.get<gpu::VsmParams>();
    const glm::vec2 moments = p.anisotropy > 0.0f
                                  ? vsmMomentsMip(vsmMipChain(in.map, p.size, in.view), in.map.size,
                                                  in.probe, p.anisotropy)
                                  : glm::vec2(momentsAt(in.map, MOMENTS_VSM, p.size,
                                                        glm::vec2(0.0f), in.view, in.probe.uv));
    const float t = gpu::momentDepth(in.view, in.probe.depth);
    const float bound = gpu::chebyshevUpperBound(moments, t, p.minVariance);
    return {gpu::snapToExtremes(gpu::reduceLightBleeding(bound, p.bleedReduction)), moments, t};
}

} // namespace

const TechniqueModule& vsmModule() {
    static const TechniqueModule module{
        .info = {.id = Technique::Vsm,
                 .name = "vsm",
                 .summary = "variance shadow maps: blurred depth moments, Chebyshev's bound on "
                            "the lit fraction (a filter of any width at a fixed cost per pixel)",
                 .reference = "Donnelly and Lauritzen 2006, 'Variance shadow maps'",
                 .families = {"bias", "vsm", "csm", "composite"},
                 .variants = {{.label = ""},
                              {.label = "no-bleed-reduction",
                               .sets = {{"vsm.bleedReduction", "0"}}},
                              {.label = "mip", .sets = {{"vsm.filter", "mip"}}}}},
        .parameters =
            {kBlur.sizeParameter(),
             {.key = "vsm.minVariance",
              .type = ParameterType::Float,
              .defaultValue = 1e-7,
              .min = 0.0,
              .max = 0.01,
              .unit = "(depth range)^2",
              .description = "least variance Chebyshev's bound assumes, in squared units of the "
                             "view's depth range (keeps flat receivers from shadowing themselves)"},
             {.key = "vsm.bleedReduction",
              .type = ParameterType::Float,
              .defaultValue = 0.2,
              .min = 0.0,
              .max = 0.99,
              .description = "bounds up to this count as shadow, the rest rescaled: less light "
                             "bleeding between stacked occluders, darker and harder penumbrae"},
             {.key = "vsm.filter",
              .type = ParameterType::Choice,
              .defaultValue = 0,
              .choices = {"blur", "mip"},
              .description = "blur: the blurred moments read bilinearly; mip: a mip chain over "
                             "them, read trilinearly over the pixel's footprint in the map (wider "
                             "where the map is minified: less aliasing far from the camera)"},
             {.key = "vsm.anisotropy",
              .type = ParameterType::Int,
              .defaultValue = 8,
              .min = 1,
              .max = 16,
              .unit = "taps",
              .description = "with vsm.filter=mip: most trilinear taps along a footprint's longer "
                             "axis (1: isotropic trilinear, blurrier at grazing angles)"}},
        .maps = vsmMaps(),
        .postPasses = vsmPasses(),
        .visibilityMaps = {"moments"},
        // vsm.filter=mip reads the pixel's footprint in the map (its uvDx, uvDy).
        .constants =
            [](const ParameterValues& p) {
                return std::vector<SpecConstant>{{SPEC_FOOTPRINT, filtersThroughMips(p) ? 1u : 0u}};
            },
        .pack =
            [](const ParameterValues& p, ParamBlock& block) {
                block.set(gpu::VsmParams{
                    .minVariance = static_cast<float>(p.number("vsm.minVariance")),
                    .bleedReduction = static_cast<float>(p.number("vsm.bleedReduction")),
                    .size = static_cast<uint32_t>(p.number("vsm.size")),
                    .anisotropy = filtersThroughMips(p)
                                      ? static_cast<float>(p.number("vsm.anisotropy"))
                                      : 0.0f});
            },
        .reference = vsmReference,
        // A footprint the mip chain widens is clipped by the map's edge as any minified texture
        // is; the guard band keeps the blur's reach.
        .blurRadiusTexels = [](const ParameterValues& p) { return kBlur.radiusTexels(p); }};
    return module;
}

} // namespace penumbra::shadows
