// The summed-area members' CPU side (cpu_tables.h).
#include "shadows/cpu_tables.h"

#include "bias.h"
#include "kernels.h"
#include "light_geometry.h"
#include "penumbra/renderer.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {

void satBox(glm::vec2 uv, float reach, float size, glm::vec2& lo, glm::vec2& hi) {
    const glm::vec2 p = uv * size;
    lo = glm::clamp(p - reach, glm::vec2(0.0f), glm::vec2(size));
    hi = glm::clamp(p + reach, glm::vec2(0.0f), glm::vec2(size));
}

namespace {

// planeTableDepth.
float planeTableDepth(uint32_t kind, const FilterProbe& r, const gpu::ShadowViewData& view,
                      const gpu::FrameData& f, glm::vec2 c, float size) {
    const glm::vec2 sides(-1e30f, f.biasParams.y > 0.0f ? 1e30f : 0.0f);
    const float z =
        gpu::momentDepth(view, gpu::receiverDepthAt(r.depth, r.gradient, c / size - r.uv, sides));
    return kind == MOMENTS_MSM ? 2.0f * z - 1.0f : z - 0.5f;
}

// planeCellMoments.
glm::vec2 planeCellMoments(uint32_t kind, const FilterProbe& r, const gpu::ShadowViewData& view,
                           const gpu::FrameData& f, glm::vec2 from, glm::vec2 to, float size) {
    const glm::vec2 c = 0.5f * (from + to), h = (0.5f / std::sqrt(3.0f)) * (to - from);
    glm::vec2 sum(0.0f);
    for (int j = -1; j <= 1; j += 2)
        for (int i = -1; i <= 1; i += 2) {
            const float z = planeTableDepth(kind, r, view, f, c + h * glm::vec2(i, j), size);
            sum += 0.25f * glm::vec2(z, z * z);
        }
    return sum;
}

struct SoftSettings {
    uint32_t kind;
    float cap, scale;
    int subdivision;
    bool refine;
};

SoftSettings softSettings(uint32_t kind, const gpu::SoftParams& p,
                          const gpu::ShadowViewData& view) {
    return {kind, gpu::kernelCap(view, p.maxRadius, p.cubeRadius), p.tableScale,
            static_cast<int>(p.subdivision), p.refine != 0u};
}

// softKernel, loop for loop.
glm::vec3 softKernel(const MomentTable& table, const SoftSettings& s, const gpu::SoftParams& p,
                     const FilterProbe& r, const gpu::ShadowViewData& view, const gpu::FrameData& f,
                     glm::vec2 lo, glm::vec2 hi, float size, bool search) {
    const glm::ivec2 cells =
        glm::clamp(glm::ivec2((hi - lo) / VSSM_MIN_CELL), glm::ivec2(1), glm::ivec2(s.subdivision));
    const glm::vec2 cell = (hi - lo) / glm::vec2(cells);
    glm::vec3 total(0.0f);
    for (int j = 0; j < cells.y; ++j)
        for (int i = 0; i < cells.x; ++i) {
            const glm::vec2 from = lo + glm::vec2(i, j) * cell;
            const glm::vec2 to(i + 1 == cells.x ? hi.x : from.x + cell.x,
                               j + 1 == cells.y ? hi.y : from.y + cell.y);
            const glm::vec4 moments = table.boxMean(s.kind, s.scale, from, to);
            const float t = planeTableDepth(s.kind, r, view, f, 0.5f * (from + to), size);
            glm::vec2 result;
            if (s.kind == MOMENTS_MSM) {
                const float bias = p.momentBias;
                result = search
                             ? gpu::momentBlockers(moments, t, bias)
                             : glm::vec2(std::clamp(1.0f - gpu::momentOcclusion(moments, t, bias),
                                                    0.0f, 1.0f),
                                         0.0f);
            } else {
                const float minVariance = p.minVariance;
                const glm::vec2 m = gpu::withoutReceiverSpread(
                    glm::vec2(moments), planeCellMoments(s.kind, r, view, f, from, to, size));
                result = search ? gpu::chebyshevBlockers(m, t, minVariance)
                                : glm::vec2(gpu::reduceLightBleeding(
                                                gpu::chebyshevUpperBound(m, t, minVariance),
                                                p.bleedReduction),
                                            0.0f);
            }
            total += glm::vec3(result, 1.0f) * (cell.x * cell.y);
        }
    return total;
}

// softBlockerDistance.
float softBlockerDistance(uint32_t kind, glm::vec3 found, const gpu::ShadowViewData& view) {
    const float z = found.y / found.x;
    return std::max(
        gpu::momentDepthDistance(view, kind == MOMENTS_MSM ? 0.5f * z + 0.5f : z + 0.5f),
        view.frustum.x);
}

} // namespace

// shadowSoftDetail.
glm::vec4 softReference(uint32_t kind, const gpu::SoftParams& p, const FilterInput& in) {
    return softReference(kind, p, in, MomentTable(in.map, in.view, kind, p.tableScale));
}

glm::vec4 softReference(uint32_t kind, const gpu::SoftParams& p, const FilterInput& in,
                        const MomentTable& table) {
    const ShadowMapView& map = in.map;
    const FilterProbe& probe = in.probe;
    const gpu::FrameData& f = in.frame;
    const gpu::ShadowViewData& view = in.view;
    const SoftSettings s = softSettings(kind, p, view);
    const float size = static_cast<float>(map.size);
    const float zReceiver = gpu::viewDistance(view, probe.depth);
    glm::vec2 lo, hi;
    satBox(probe.uv, std::clamp(gpu::momentSearchRadius(view, zReceiver, map.size), 0.5f, s.cap),
           size, lo, hi);
    glm::vec3 found = softKernel(table, s, p, probe, view, f, lo, hi, size, true);
    if (found.x <= VSSM_NO_BLOCKERS * found.z) {
        satBox(probe.uv, VSSM_NARROW_SEARCH, size, lo, hi);
        found = softKernel(table, s, p, probe, view, f, lo, hi, size, true);
    }
    if (found.x <= VSSM_NO_BLOCKERS * found.z)
        return {1.0f, 1.0f, 0.0f, 0.0f};
    float radius =
        gpu::penumbraRadius(view, zReceiver, softBlockerDistance(kind, found, view), map.size);
    for (int step = 0; step < (s.refine ? VSSM_REFINE_STEPS : 0); ++step) {
        satBox(probe.uv, VSSM_BOX_PER_RADIUS * std::clamp(radius, 0.5f, s.cap), size, lo, hi);
        found = softKernel(table, s, p, probe, view, f, lo, hi, size, true);
        if (found.x <= VSSM_NO_BLOCKERS * found.z)
            return {1.0f, 1.0f, 0.0f, 0.0f};
        radius =
            std::min(radius, gpu::penumbraRadius(view, zReceiver,
                                                 softBlockerDistance(kind, found, view), map.size));
    }
    radius = std::clamp(radius, 0.5f, s.cap);
    satBox(probe.uv, VSSM_BOX_PER_RADIUS * radius, size, lo, hi);
    const glm::vec3 lit = softKernel(table, s, p, probe, view, f, lo, hi, size, false);
    return {gpu::snapToExtremes(lit.x / std::max(lit.z, 1e-6f)), found.y / found.x,
            found.x / found.z, radius};
}

} // namespace penumbra::shadows
