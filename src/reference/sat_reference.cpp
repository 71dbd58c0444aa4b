#include "reference/sat_reference.h"

#include "kernels.h"
#include "bias.h"
#include "light_geometry.h"
#include "moments.h"
#include "frame_block.h"

#include <algorithm>
#include <vector>

namespace penumbra {
namespace {

// A summed-area table of fixed-point moments as the two scan passes write it (sat_scan.glsl):
// wrapping uint sums along rows, then down columns.
class MomentTable {
public:
    MomentTable(const ShadowMapView& map, const gpu::ShadowViewData& view, uint32_t kind,
                float scale)
        : n_(static_cast<int>(map.size)),
          table_(static_cast<size_t>(n_) * static_cast<size_t>(n_)) {
        std::vector<glm::uvec4> rows(table_.size());
        for (int j = 0; j < n_; ++j) {
            glm::uvec4 sum(0u);
            for (int i = 0; i < n_; ++i) {
                sum += gpu::tableMoments(kind, gpu::momentDepth(view, map.texel(i, j)), scale);
                rows[at(i, j)] = sum;
            }
        }
        for (int i = 0; i < n_; ++i) {
            glm::uvec4 sum(0u);
            for (int j = 0; j < n_; ++j) {
                sum += rows[at(i, j)];
                table_[at(i, j)] = sum;
            }
        }
    }

    // tableBoxSum, loop for loop.
    glm::vec4 boxSum(glm::vec2 lo, glm::vec2 hi) const {
        const glm::ivec2 a = glm::min(glm::ivec2(glm::floor(lo)), glm::ivec2(n_ - 1));
        const glm::ivec2 b = glm::min(glm::ivec2(glm::floor(hi)), glm::ivec2(n_ - 1));
        const glm::vec2 fa = lo - glm::vec2(a), fb = hi - glm::vec2(b);
        const int xs[4] = {a.x, a.x + 1, b.x, b.x + 1}, ys[4] = {a.y, a.y + 1, b.y, b.y + 1};
        const float wx[4] = {1.0f - fa.x, fa.x, 1.0f - fb.x, fb.x};
        const float wy[4] = {1.0f - fa.y, fa.y, 1.0f - fb.y, fb.y};
        glm::uvec4 c[4][4];
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i)
                c[j][i] = corner({xs[i], ys[j]});
        glm::vec4 sum(0.0f);
        for (int y0 = 0; y0 < 2; ++y0)
            for (int y1 = 2; y1 < 4; ++y1)
                for (int x0 = 0; x0 < 2; ++x0)
                    for (int x1 = 2; x1 < 4; ++x1)
                        sum += wy[y0] * wy[y1] * wx[x0] * wx[x1] *
                               gpu::boxFromCorners(c[y0][x0], c[y0][x1], c[y1][x0], c[y1][x1]);
        return sum;
    }

    // tableBoxMean.
    glm::vec4 boxMean(uint32_t kind, float scale, glm::vec2 lo, glm::vec2 hi) const {
        const float area = std::max((hi.x - lo.x) * (hi.y - lo.y), 1e-6f);
        return gpu::tableMean(kind, boxSum(lo, hi) / area, scale);
    }

private:
    size_t at(int i, int j) const {
        return static_cast<size_t>(j) * static_cast<size_t>(n_) + static_cast<size_t>(i);
    }
    glm::uvec4 corner(glm::ivec2 c) const {
        return c.x <= 0 || c.y <= 0 ? glm::uvec4(0u) : table_[at(c.x - 1, c.y - 1)];
    }

    int n_;
    std::vector<glm::uvec4> table_;
};

// satBox: the box of half-width `reach` texels around uv, cut to the map.
void satBox(glm::vec2 uv, float reach, float size, glm::vec2& lo, glm::vec2& hi) {
    const glm::vec2 p = uv * size;
    lo = glm::clamp(p - reach, glm::vec2(0.0f), glm::vec2(size));
    hi = glm::clamp(p + reach, glm::vec2(0.0f), glm::vec2(size));
}

// planeTableDepth.
float planeTableDepth(uint32_t kind, const FilterProbe& r, const gpu::ShadowViewData& view,
                      const gpu::FrameData& f, glm::vec2 c, float size) {
    const glm::vec2 sides(-1e30f, f.biasParams.y > 0.0f ? 1e30f : 0.0f);
    const float z =
        gpu::momentDepth(view, gpu::receiverDepthAt(r.depth, r.gradient, c / size - r.uv, sides));
    return kind == MOMENTS_MSM ? 2.0f * z - 1.0f : z - 0.5f;
}

struct SoftSettings {
    uint32_t kind;
    float cap, scale;
    int subdivision;
    bool refine;
};

SoftSettings softSettings(uint32_t kind, const gpu::FrameData& f) {
    if (kind == MOMENTS_MSM)
        return {kind, f.msmSoftParams.x, f.tableScales.z, static_cast<int>(f.softMode.z),
                f.softMode.w != 0u};
    return {kind, f.vssmParams.x, f.tableScales.y, static_cast<int>(f.softMode.x),
            f.softMode.y != 0u};
}

// softKernel, loop for loop.
glm::vec3 softKernel(const MomentTable& table, const SoftSettings& s, const FilterProbe& r,
                     const gpu::ShadowViewData& view, const gpu::FrameData& f, glm::vec2 lo,
                     glm::vec2 hi, float size, bool search) {
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
                const float bias = f.msmSoftParams.y;
                result = search
                             ? gpu::momentBlockers(moments, t, bias)
                             : glm::vec2(std::clamp(1.0f - gpu::momentOcclusion(moments, t, bias),
                                                    0.0f, 1.0f),
                                         0.0f);
            } else {
                const float minVariance = f.vssmParams.y;
                const glm::vec2 m(moments);
                result = search ? gpu::chebyshevBlockers(m, t, minVariance)
                                : glm::vec2(gpu::reduceLightBleeding(
                                                gpu::chebyshevUpperBound(m, t, minVariance),
                                                f.vssmParams.z),
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

// shadowSoftDetail.
glm::vec4 softReference(uint32_t kind, const ShadowMapView& map, const FilterProbe& probe,
                        const gpu::FrameData& f, const gpu::ShadowViewData& view) {
    const SoftSettings s = softSettings(kind, f);
    const MomentTable table(map, view, kind, s.scale);
    const float size = static_cast<float>(map.size);
    const float zReceiver = gpu::viewDistance(view, probe.depth);
    glm::vec2 lo, hi;
    satBox(probe.uv, std::clamp(gpu::momentSearchRadius(view, zReceiver, map.size), 0.5f, s.cap),
           size, lo, hi);
    glm::vec3 found = softKernel(table, s, probe, view, f, lo, hi, size, true);
    if (found.x <= VSSM_NO_BLOCKERS * found.z)
        return {1.0f, 1.0f, 0.0f, 0.0f};
    float radius =
        gpu::penumbraRadius(view, zReceiver, softBlockerDistance(kind, found, view), map.size);
    if (s.refine) {
        satBox(probe.uv, VSSM_BOX_PER_RADIUS * std::clamp(radius, 0.5f, s.cap), size, lo, hi);
        found = softKernel(table, s, probe, view, f, lo, hi, size, true);
        if (found.x <= VSSM_NO_BLOCKERS * found.z)
            return {1.0f, 1.0f, 0.0f, 0.0f};
        radius =
            std::min(radius, gpu::penumbraRadius(view, zReceiver,
                                                 softBlockerDistance(kind, found, view), map.size));
    }
    radius = std::clamp(radius, 0.5f, s.cap);
    satBox(probe.uv, VSSM_BOX_PER_RADIUS * radius, size, lo, hi);
    const glm::vec3 lit = softKernel(table, s, probe, view, f, lo, hi, size, false);
    return {gpu::snapToExtremes(lit.x / std::max(lit.z, 1e-6f)), found.y / found.x,
            found.x / found.z, radius};
}

} // namespace

glm::vec4 savsmReference(const ShadowMapView& map, const FilterProbe& probe,
                         const gpu::FrameData& f, const gpu::ShadowViewData& view) {
    const MomentTable table(map, view, MOMENTS_VSM, f.tableScales.x);
    const float size = static_cast<float>(map.size);
    glm::vec2 lo, hi;
    satBox(probe.uv, 0.5f * std::max(f.savsmParams.x * view.cascade.z, 1.0f), size, lo, hi);
    const glm::vec2 moments(table.boxMean(MOMENTS_VSM, f.tableScales.x, lo, hi));
    const float t = gpu::momentDepth(view, probe.depth) - 0.5f;
    const float v = gpu::chebyshevUpperBound(moments, t, f.savsmParams.y);
    return {gpu::snapToExtremes(gpu::reduceLightBleeding(v, f.savsmParams.z)), moments, t};
}

glm::vec4 vssmReference(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
                        const gpu::ShadowViewData& view) {
    return softReference(MOMENTS_VSM, map, probe, f, view);
}

glm::vec4 msmSoftReference(const ShadowMapView& map, const FilterProbe& probe,
                           const gpu::FrameData& f, const gpu::ShadowViewData& view) {
    return softReference(MOMENTS_MSM, map, probe, f, view);
}

} // namespace penumbra
