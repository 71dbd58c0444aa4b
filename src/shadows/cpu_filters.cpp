// The CPU side of shaders/include/receiver.glsl and shadow_hard.glsl, operation for operation.
#include "shadows/cpu_filters.h"

#include "bias.h"
#include "kernels.h"
#include "penumbra/renderer.h"

#include <algorithm>
#include <cmath>

namespace penumbra::shadows {

float texelTest(const CpuReceiver& r, float stored, glm::vec2 texelUv, glm::vec2 dzRange,
                const MarginTracker& m) {
    const glm::vec2 range(std::max(dzRange.x, r.planeRange.x), std::min(dzRange.y, r.planeRange.y));
    const float receiver = gpu::tapDepth(r.depth, r.gradient, texelUv - r.uv, range, r.curve);
    m.see(receiver, stored);
    return gpu::depthTest(receiver, stored);
}

// x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j): textureGather's order.
glm::vec4 gatherTests(const ShadowMapView& map, glm::ivec2 base, float size, const CpuReceiver& r,
                      glm::vec2 dzRange, const MarginTracker& m) {
    const glm::vec2 c = (glm::vec2(base) + 0.5f) / size;
    const float t = 1.0f / size;
    const glm::vec4 depths(map.texel(base.x, base.y + 1), map.texel(base.x + 1, base.y + 1),
                           map.texel(base.x + 1, base.y), map.texel(base.x, base.y));
    const glm::vec4 tests(texelTest(r, depths.x, c + glm::vec2(0.0f, t), dzRange, m),
                          texelTest(r, depths.y, c + glm::vec2(t, t), dzRange, m),
                          texelTest(r, depths.z, c + glm::vec2(t, 0.0f), dzRange, m),
                          texelTest(r, depths.w, c, dzRange, m));
    const glm::vec2 offset = r.uv - c - 0.5f * t;
    const float slopeLimit = r.creaseLimit;
    const float margin = CREASE_MARGIN_TEXELS * t * r.curve.y;
    if (slopeLimit > 0.0f) { // the crease rule's two decisions, as close calls for the probes
        const glm::vec2 g = gpu::gatherGradient(depths, t);
        m.see(glm::length(g) / slopeLimit, 1.0f); // relative: the limit is in depth per uv
        m.see(0.25f * (depths.x + depths.y + depths.z + depths.w) + glm::dot(g, offset),
              r.depth + margin);
    }
    return gpu::creaseTests(tests, depths, offset, t, r.depth, slopeLimit, margin);
}

float bilinearTap(const ShadowMapView& map, glm::vec2 texelPos, float size, const CpuReceiver& r,
                  glm::vec2 dzRange, const MarginTracker& m, uint32_t subTexelBits) {
    const glm::vec2 p = texelPos - 0.5f;
    const glm::vec2 base = glm::floor(p);
    glm::vec2 f = p - base;
    if (subTexelBits > 0) { // hardware filtering keeps this many bits of the fraction
        const float steps = std::ldexp(1.0f, static_cast<int>(subTexelBits));
        f = glm::round(f * steps) / steps;
    }
    return gpu::bilinearMix(gatherTests(map, glm::ivec2(base), size, r, dzRange, m), f);
}

float pcfGrid(const ShadowMapView& map, const CpuReceiver& r, uint32_t filterKind, int n,
              float sigma, glm::vec2 dzRange, const MarginTracker& m) {
    const float size = static_cast<float>(map.size);
    const glm::vec2 p = r.uv * size - 0.5f;
    const glm::vec2 base = glm::floor(p);
    const glm::vec2 f = p - base;
    float cx[PCF_MAX_SIZE + 1], cy[PCF_MAX_SIZE + 1];
    gpu::footprintWeights(filterKind, n, sigma, f.x, cx);
    gpu::footprintWeights(filterKind, n, sigma, f.y, cy);
    const glm::ivec2 first = glm::ivec2(base) - (n - 1) / 2;
    float sum = 0.0f;
    for (int ky = 0; ky <= n; ky += 2)
        for (int kx = 0; kx <= n; kx += 2) {
            const glm::vec4 t = gatherTests(map, first + glm::ivec2(kx, ky), size, r, dzRange, m);
            sum += (t.w * cx[kx] + t.z * cx[kx + 1]) * cy[ky] +
                   (t.x * cx[kx] + t.y * cx[kx + 1]) * cy[ky + 1];
        }
    return sum;
}

glm::vec2 poissonPoint(const gpu::FrameData& f, uint32_t i) {
    const glm::vec4 pair = f.poisson[i / 2];
    return i % 2 == 0 ? glm::vec2(pair.x, pair.y) : glm::vec2(pair.z, pair.w);
}

float poissonTaps(const ShadowMapView& map, const CpuReceiver& r, const gpu::FrameData& f,
                  uint32_t n, float radius, float turns, glm::vec2 dzRange,
                  const MarginTracker& m) {
    const float size = static_cast<float>(map.size);
    const glm::vec2 centre = r.uv * size;
    float sum = 0.0f;
    for (uint32_t i = 0; i < n; ++i)
        sum += bilinearTap(map, centre + gpu::rotatedOffset(poissonPoint(f, i), turns, radius),
                           size, r, dzRange, m);
    return sum / static_cast<float>(n);
}

CpuReceiver receiverOf(const FilterProbe& p) {
    return {p.uv, p.depth, p.gradient, p.curve, p.planeRange, p.creaseLimit};
}

float hardTest(const ShadowMapView& map, const FilterProbe& probe, const MarginTracker& m,
               glm::vec2 dzRange) {
    const int last = static_cast<int>(map.size) - 1;
    const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(probe.uv * float(map.size))),
                                        glm::ivec2(0), glm::ivec2(last));
    const glm::vec2 centre = (glm::vec2(texel) + 0.5f) / static_cast<float>(map.size);
    return texelTest(receiverOf(probe), map.texel(texel.x, texel.y), centre, dzRange, m);
}
} // namespace penumbra::shadows
