// Layer `contact`: screen-space contact shadows [Sousa et al. 2011, "Secrets of CryENGINE 3
// graphics technology" (screen-space self-shadowing); as Unreal Engine 4's contact shadows,
// Filament's and Unity HDRP's]: from each pixel, march the depth buffer towards the light; a
// surface found in front of a sample (by less than its assumed thickness) shadows the pixel,
// which multiplies the light's visibility from its base technique, whatever that is. It restores
// what a shadow map cannot hold: contact shadows that its bias detaches from their casters
// (peter-panning), and detail finer than its texels. Its cost: false shadow where the depth
// buffer hides how thin an object is (the thickness a surface is assumed to have behind it). The
// G-buffer's surfaces are taken as their triangles' planes (shaders/include/contact_march.h), so a
// receiver never shadows itself. Shader: shaders/contact.comp; CPU mirror: contactReference.
#include "shadows/contact.h"

#include "kernels.h"
#include "shadows/layer.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace penumbra::shadows {
namespace {

// contact.thickness 0: this fraction of the march's length. Measured (docs/techniques.md,
// "Contact shadows"): thicker finds more contacts behind solid objects, and more false shadow
// behind thin ones.
constexpr float kAutoThickness = 0.5f;

} // namespace

gpu::ContactParams contactParams(const ParameterValues& p) {
    const auto length = static_cast<float>(p.number("contact.length"));
    const auto thickness = static_cast<float>(p.number("contact.thickness"));
    return {.marchLength = length,
            .steps = static_cast<uint32_t>(p.number("contact.steps")),
            .thickness = thickness > 0.0f ? thickness : kAutoThickness * length};
}

std::vector<float> contactReference(const ScreenGBuffer& g, const gpu::FrameData& frame,
                                    const Light& light, const gpu::ContactParams& params) {
    const size_t pixels = size_t{g.width} * g.height;
    std::vector<float> out(pixels, std::numeric_limits<float>::quiet_NaN());
    auto at = [&](std::span<const float> image, glm::ivec2 p) {
        const size_t i = 3 * (size_t(p.y) * g.width + size_t(p.x));
        return glm::vec3(image[i], image[i + 1], image[i + 2]);
    };
    const glm::vec2 size(static_cast<float>(g.width), static_cast<float>(g.height));
    for (uint32_t y = 0; y < g.height; ++y)
        for (uint32_t x = 0; x < g.width; ++x) {
            const glm::ivec2 p(x, y);
            const glm::vec3 world = at(g.position, p);
            if (std::isnan(world.x))
                continue;
            // contactVisibility
            const glm::vec3 toLight = light.type == LightType::Directional
                                          ? -glm::normalize(light.direction)
                                          : glm::normalize(light.position - world);
            float& c = out[size_t(y) * g.width + x];
            c = 1.0f;
            const float nDotL = glm::dot(at(g.faceNormal, p), toLight);
            if (nDotL <= 0.0f)
                continue;
            float reach = params.marchLength;
            if (light.type != LightType::Directional)
                reach = std::min(reach, glm::length(light.position - world));
            const float jitter = gpu::rotationTurns(ROTATION_IGN, glm::uvec2(p));
            for (uint32_t i = 0; i < params.steps; ++i) {
                const float t = gpu::contactSampleDistance(i, params.steps, reach, jitter);
                const glm::vec3 q = world + toLight * t;
                glm::vec3 ndc;
                glm::vec2 pixel;
                if (!gpu::contactProject(frame.viewProj, q, size, ndc, pixel))
                    break;
                const float tolerance = gpu::contactTolerance(
                    frame.invViewProj, ndc, size.x, reach / static_cast<float>(params.steps));
                const glm::vec3 near = gpu::unprojectNdc(frame.invViewProj, {ndc.x, ndc.y, 1.0f});
                const glm::ivec2 base = gpu::contactTexels(pixel, {g.width, g.height});
                float hidden = 0.0f;
                for (int k = 0; k < 4; ++k) {
                    const glm::ivec2 s = base + glm::ivec2(k & 1, k >> 1);
                    const glm::vec3 surface = at(g.position, s);
                    if (!std::isnan(surface.x) &&
                        gpu::contactOccludes(q, near, surface, at(g.faceNormal, s), tolerance,
                                             params.thickness))
                        hidden += gpu::contactTexelWeight(pixel, base, k);
                }
                if (hidden >= 0.75f) {
                    c = 0.0f;
                    break;
                }
            }
        }
    return out;
}

const LayerModule& contactLayer() {
    static const LayerModule layer{
        .name = "contact",
        .summary = "screen-space contact shadows: the depth buffer marched towards the light "
                   "from each pixel, on top of any technique",
        .reference = "Sousa et al. 2011, 'Secrets of CryENGINE 3 graphics technology' "
                     "(screen-space self-shadowing); contact shadows as in Unreal Engine 4, "
                     "Filament and Unity HDRP",
        .parameters = {{.key = "contact.length",
                        .type = ParameterType::Float,
                        .defaultValue = 0.0,
                        .min = 0.0,
                        .max = 1e6,
                        .unit = "world units",
                        .description =
                            "how far each pixel marches towards the light through the depth "
                            "buffer (0: off, the layer does not run)"},
                       {.key = "contact.steps",
                        .type = ParameterType::Int,
                        .defaultValue = 16,
                        .min = 1,
                        .max = 256,
                        .unit = "samples",
                        .description = "samples along the march (jittered per pixel by interleaved "
                                       "gradient noise)"},
                       {.key = "contact.thickness",
                        .type = ParameterType::Float,
                        .defaultValue = 0.0,
                        .min = 0.0,
                        .max = 1e6,
                        .unit = "world units",
                        .description =
                            "how deep a surface in the depth buffer is taken to be (a body's "
                            "chord: less at a grazing view): a sample further behind it is not "
                            "hidden (0: half of contact.length)"}},
        .enabled = [](const ParameterValues& p) { return p.number("contact.length") > 0.0; },
        .off = {"contact.length", "0"},
        .shader = "contact.comp",
        .pack = [](const ParameterValues& p, ParamBlock& block) { block.set(contactParams(p)); },
        .rowSettings =
            [](double sceneRadius) {
                return std::vector<std::pair<std::string, std::string>>{
                    {"contact.length", fmt::format("{:.6g}", kContactRowFraction * sceneRadius)}};
            },
        .rows = {"hard", "pcf[box3]"}};
    return layer;
}

} // namespace penumbra::shadows
