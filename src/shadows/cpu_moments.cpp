// The CPU side of the blurred-moment family's maps: shaders/include/moments_blur.glsl, vsm_mip.comp
// and shadow_moments.glsl's reads, operation for operation.
#include "shadows/cpu_moments.h"

#include "kernels.h"
#include "moments.h"
#include "penumbra/renderer.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {

// The prefiltered family (shaders/include/moments_blur.glsl, shadow_moments.glsl). What texel
// (i, j) of the blurred map holds after the two post passes: the row pass's warpedMoments of
// momentDepth, then the column pass over those, each a normalised Gaussian with clamp-to-edge.
glm::vec4 blurredMoments(const ShadowMapView& map, uint32_t kind, uint32_t taps,
                         glm::vec2 exponents, const gpu::ShadowViewData& view, int i, int j) {
    const int last = static_cast<int>(map.size) - 1;
    i = std::clamp(i, 0, last), j = std::clamp(j, 0, last); // the gather's clamp-to-edge
    const int n = gpu::scaledKernelSize(taps, view.cascade.z);
    const int reach = (n - 1) / 2;
    auto rowPass = [&](int y) {
        glm::vec4 sum(0.0f);
        float weights = 0.0f;
        for (int k = -reach; k <= reach; ++k) {
            const float w = gpu::gaussianTap(k, n);
            const float z = gpu::momentDepth(view, map.texel(std::clamp(i + k, 0, last), y));
            sum += w * gpu::warpedMoments(kind, z, exponents);
            weights += w;
        }
        return sum / weights;
    };
    glm::vec4 sum(0.0f);
    float weights = 0.0f;
    for (int k = -reach; k <= reach; ++k) {
        const float w = gpu::gaussianTap(k, n);
        sum += w * rowPass(std::clamp(j + k, 0, last));
        weights += w;
    }
    return sum / weights;
}

// The blurred map at the probe, bilinear over the four texels around it (textureGather's order).
// `stored`: what the blurred map holds of a texel's moments (msm.precision=16 quantises them).
glm::vec4 momentsAt(const ShadowMapView& map, uint32_t kind, uint32_t taps, glm::vec2 exponents,
                    const gpu::ShadowViewData& view, glm::vec2 uv, glm::vec4 (*stored)(glm::vec4)) {
    const glm::vec2 p = uv * static_cast<float>(map.size) - 0.5f;
    const glm::vec2 base = glm::floor(p);
    const glm::vec2 frac = p - base;
    const auto b = glm::ivec2(base);
    glm::vec4 x = blurredMoments(map, kind, taps, exponents, view, b.x, b.y + 1);
    glm::vec4 y = blurredMoments(map, kind, taps, exponents, view, b.x + 1, b.y + 1);
    glm::vec4 z = blurredMoments(map, kind, taps, exponents, view, b.x + 1, b.y);
    glm::vec4 w = blurredMoments(map, kind, taps, exponents, view, b.x, b.y);
    if (stored)
        x = stored(x), y = stored(y), z = stored(z), w = stored(w);
    glm::vec4 m;
    for (int c = 0; c < 4; ++c)
        m[c] = gpu::bilinearMix({x[c], y[c], z[c], w[c]}, frac);
    return m;
}

// vsm.filter=mip: the blurred moments' mip chain (vsm_mip.comp), level by level.
std::vector<std::vector<glm::vec2>> vsmMipChain(const ShadowMapView& map, uint32_t taps,
                                                const gpu::ShadowViewData& view) {
    const auto n = static_cast<int>(map.size);
    std::vector<std::vector<glm::vec2>> chain(1, std::vector<glm::vec2>(size_t(n) * n));
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            chain[0][size_t(j) * n + i] =
                glm::vec2(blurredMoments(map, MOMENTS_VSM, taps, glm::vec2(0.0f), view, i, j));
    for (int size = n / 2, above = n; size > 0; above = size, size /= 2) {
        const std::vector<glm::vec2>& a = chain.back();
        std::vector<glm::vec2> level(size_t(size) * size);
        auto at = [&](int x, int y) {
            return a[size_t(std::min(y, above - 1)) * above + std::min(x, above - 1)];
        };
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                level[size_t(y) * size + x] =
                    0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) +
                             at(2 * x + 1, 2 * y + 1));
        chain.push_back(std::move(level));
    }
    return chain;
}

// momentsAtLevel and momentsMip of shaders/include/shadow_moments.glsl.
glm::vec2 vsmMomentsMip(const std::vector<std::vector<glm::vec2>>& chain, uint32_t mapSize,
                        const FilterProbe& probe, float maxTaps) {
    auto atLevel = [&](glm::vec2 uv, int level) {
        const int size = std::max(static_cast<int>(mapSize) >> level, 1);
        const glm::vec2 p = uv * static_cast<float>(size) - 0.5f;
        const glm::vec2 base = glm::floor(p);
        const glm::vec2 frac = p - base;
        const auto b = glm::ivec2(base);
        auto texel = [&](int x, int y) {
            return chain[size_t(level)]
                        [size_t(std::clamp(y, 0, size - 1)) * size + std::clamp(x, 0, size - 1)];
        };
        const glm::vec2 t00 = texel(b.x, b.y), t10 = texel(b.x + 1, b.y), t01 = texel(b.x, b.y + 1),
                        t11 = texel(b.x + 1, b.y + 1);
        glm::vec2 m;
        for (int c = 0; c < 2; ++c)
            m[c] = gpu::bilinearMix({t01[c], t11[c], t10[c], t00[c]}, frac);
        return m;
    };
    const auto maxLevel = static_cast<float>(gpu::mipLevelCount(mapSize) - 1u);
    const glm::vec4 footprint =
        gpu::mipFootprint(probe.uvDx, probe.uvDy, static_cast<float>(mapSize), maxTaps, maxLevel);
    const auto fine = static_cast<int>(std::floor(footprint.x));
    const int coarse = std::min(fine + 1, static_cast<int>(maxLevel));
    const float blend = footprint.x - static_cast<float>(fine);
    const auto taps = static_cast<int>(footprint.y);
    glm::vec2 sum(0.0f);
    for (int k = 0; k < taps; ++k) {
        const glm::vec2 uv =
            probe.uv + gpu::mipTapOffset(k, taps) * glm::vec2(footprint.z, footprint.w);
        const glm::vec2 a = atLevel(uv, fine), b = atLevel(uv, coarse);
        sum += a + (b - a) * blend;
    }
    return sum / static_cast<float>(taps);
}

} // namespace penumbra::shadows
