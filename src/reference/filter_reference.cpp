#include "reference/filter_reference.h"

#include "kernels.h"
#include "bias.h"
#include "light_geometry.h"
#include "moments.h"
#include "frame_block.h"
#include "penumbra/error.h"
#include "reference/sampling.h"
#include "reference/sat_reference.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra {
namespace {

struct Receiver {
    glm::vec2 uv;
    float depth;
    glm::vec2 gradient;
    glm::vec2 curve{0.0f}, planeRange{-1e30f, 1e30f}; // bias.mode=adaptive (FilterProbe's)
};

// Records how close each comparison comes to a tie, when asked.
struct MarginTracker {
    float* margin = nullptr;
    void see(float a, float b) const {
        if (margin)
            *margin = std::min(*margin, std::abs(a - b));
    }
};

float texelTest(const Receiver& r, float stored, glm::vec2 texelUv, glm::vec2 dzRange,
                const MarginTracker& m) {
    const glm::vec2 range(std::max(dzRange.x, r.planeRange.x), std::min(dzRange.y, r.planeRange.y));
    const float receiver = gpu::tapDepth(r.depth, r.gradient, texelUv - r.uv, range, r.curve);
    m.see(receiver, stored);
    return gpu::depthTest(receiver, stored);
}

// x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j): textureGather's order.
glm::vec4 gatherTests(const ShadowMapView& map, glm::ivec2 base, float size, const Receiver& r,
                      glm::vec2 dzRange, const MarginTracker& m) {
    const glm::vec2 c = (glm::vec2(base) + 0.5f) / size;
    const float t = 1.0f / size;
    return {texelTest(r, map.texel(base.x, base.y + 1), c + glm::vec2(0.0f, t), dzRange, m),
            texelTest(r, map.texel(base.x + 1, base.y + 1), c + glm::vec2(t, t), dzRange, m),
            texelTest(r, map.texel(base.x + 1, base.y), c + glm::vec2(t, 0.0f), dzRange, m),
            texelTest(r, map.texel(base.x, base.y), c, dzRange, m)};
}

float bilinearTap(const ShadowMapView& map, glm::vec2 texelPos, float size, const Receiver& r,
                  glm::vec2 dzRange, const MarginTracker& m, uint32_t subTexelBits = 0) {
    const glm::vec2 p = texelPos - 0.5f;
    const glm::vec2 base = glm::floor(p);
    glm::vec2 f = p - base;
    if (subTexelBits > 0) { // hardware filtering keeps this many bits of the fraction
        const float steps = std::ldexp(1.0f, static_cast<int>(subTexelBits));
        f = glm::round(f * steps) / steps;
    }
    return gpu::bilinearMix(gatherTests(map, glm::ivec2(base), size, r, dzRange, m), f);
}

constexpr int kMaxSize = PCF_MAX_SIZE;

float pcfGrid(const ShadowMapView& map, const Receiver& r, uint32_t filterKind, int n, float sigma,
              glm::vec2 dzRange, const MarginTracker& m) {
    const float size = static_cast<float>(map.size);
    const glm::vec2 p = r.uv * size - 0.5f;
    const glm::vec2 base = glm::floor(p);
    const glm::vec2 f = p - base;
    float cx[kMaxSize + 1], cy[kMaxSize + 1];
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

float poissonTaps(const ShadowMapView& map, const Receiver& r, const gpu::FrameData& f, uint32_t n,
                  float radius, float turns, glm::vec2 dzRange, const MarginTracker& m) {
    const float size = static_cast<float>(map.size);
    const glm::vec2 centre = r.uv * size;
    float sum = 0.0f;
    for (uint32_t i = 0; i < n; ++i)
        sum += bilinearTap(map, centre + gpu::rotatedOffset(poissonPoint(f, i), turns, radius),
                           size, r, dzRange, m);
    return sum / static_cast<float>(n);
}

float pcfPoisson(const ShadowMapView& map, const Receiver& r, const gpu::FrameData& f,
                 glm::uvec2 pixel, glm::vec2 dzRange, const MarginTracker& m) {
    return poissonTaps(map, r, f, f.filterMode.z, f.filterParams.x,
                       gpu::rotationTurns(f.filterMode.w, pixel), dzRange, m);
}

bool probeDecides(const ShadowMapView& map, const Receiver& r, const gpu::FrameData& f,
                  glm::vec2 dzRange, const MarginTracker& m, float& result) {
    const float reach = f.filterMode.x == FILTER_POISSON
                            ? f.filterParams.x * 0.70710678f
                            : 0.5f * static_cast<float>(f.filterMode.y - 1u);
    const float size = static_cast<float>(map.size);
    const glm::vec2 centre = r.uv * size;
    const float sum = bilinearTap(map, centre + glm::vec2(-reach, -reach), size, r, dzRange, m) +
                      bilinearTap(map, centre + glm::vec2(reach, -reach), size, r, dzRange, m) +
                      bilinearTap(map, centre + glm::vec2(-reach, reach), size, r, dzRange, m) +
                      bilinearTap(map, centre + glm::vec2(reach, reach), size, r, dzRange, m);
    result = sum * 0.25f;
    return sum == 0.0f || sum == 4.0f;
}

Receiver receiverOf(const FilterProbe& p) {
    return {p.uv, p.depth, p.gradient, p.curve, p.planeRange};
}

float pcfUnsnapped(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
                   const MarginTracker& m) {
    const Receiver r = receiverOf(probe);
    const uint32_t filterKind = f.filterMode.x;
    const glm::vec2 dzRange(f.biasParams.x, f.biasParams.y);
    const float size = static_cast<float>(map.size);
    if (filterKind == FILTER_HARDWARE) {
        const float lift =
            f.biasMode.w == BIAS_ADAPTIVE ? gpu::footprintLift(r.gradient, size, -dzRange.x) : 0.0f;
        return bilinearTap(map, r.uv * size, size, Receiver{r.uv, r.depth - lift, glm::vec2(0.0f)},
                           dzRange, m, f.biasMode.y != 0u ? f.biasMode.z : 0u);
    }
    float early = 0.0f;
    if (f.filterParams.z != 0.0f && filterKind != FILTER_BILINEAR &&
        probeDecides(map, r, f, dzRange, m, early))
        return early;
    if (filterKind == FILTER_POISSON)
        return pcfPoisson(map, r, f, probe.pixel, dzRange, m);
    const int n = filterKind == FILTER_BILINEAR ? 1 : static_cast<int>(f.filterMode.y);
    return pcfGrid(map, r, filterKind, n, f.filterParams.y, dzRange, m);
}

float pcf(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
          const MarginTracker& m) {
    return gpu::snapToExtremes(pcfUnsnapped(map, probe, f, m));
}

float hard(const ShadowMapView& map, const FilterProbe& probe, const MarginTracker& m,
           glm::vec2 dzRange) {
    const int last = static_cast<int>(map.size) - 1;
    const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(probe.uv * float(map.size))),
                                        glm::ivec2(0), glm::ivec2(last));
    const glm::vec2 centre = (glm::vec2(texel) + 0.5f) / static_cast<float>(map.size);
    return texelTest(receiverOf(probe), map.texel(texel.x, texel.y), centre, dzRange, m);
}

// shadow_pcss.glsl's loops, transcribed; its geometry is light_geometry.h's.
float searchBlockers(const ShadowMapView& map, const Receiver& r, const gpu::FrameData& f,
                     uint32_t n, float radius, float turns, glm::vec2 dzRange,
                     const MarginTracker& m, float& averageDepth) {
    const float size = static_cast<float>(map.size);
    const glm::vec2 centre = r.uv * size;
    float sum = 0.0f, count = 0.0f;
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec2 p = centre + gpu::rotatedOffset(poissonPoint(f, i), turns, radius) - 0.5f;
        const glm::ivec2 base = glm::ivec2(glm::floor(p));
        const glm::vec4 depths(map.texel(base.x, base.y + 1), map.texel(base.x + 1, base.y + 1),
                               map.texel(base.x + 1, base.y), map.texel(base.x, base.y));
        const glm::vec4 blocks = glm::vec4(1.0f) - gatherTests(map, base, size, r, dzRange, m);
        sum += glm::dot(blocks, depths);
        count += blocks.x + blocks.y + blocks.z + blocks.w;
    }
    averageDepth = count > 0.0f ? sum / count : 1.0f;
    return count;
}

glm::vec4 pcss(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
               const gpu::ShadowViewData& view, const MarginTracker& m) {
    const Receiver r = receiverOf(probe);
    const glm::vec2 dzRange(f.biasParams.x, f.biasParams.y);
    const float turns = gpu::rotationTurns(f.pcssMode.z, probe.pixel);
    const float maxRadius = f.pcssParams.x;
    const float zReceiver = gpu::viewDistance(view, r.depth);
    const float search = std::min(gpu::blockerSearchRadius(view, zReceiver, map.size), maxRadius);
    float blockerDepth = 1.0f;
    const uint32_t searchTaps = f.pcssMode.x;
    const float blockers = searchBlockers(map, r, f, searchTaps, std::max(search, 0.5f), turns,
                                          dzRange, m, blockerDepth);
    if (blockers == 0.0f)
        return {1.0f, blockerDepth, 0.0f, 0.0f};
    const float zBlocker = gpu::viewDistance(view, blockerDepth);
    const float radius =
        std::clamp(gpu::penumbraRadius(view, zReceiver, zBlocker, map.size), 0.5f, maxRadius);
    if (blockers == 4.0f * static_cast<float>(searchTaps) && radius <= 1.0f)
        return {0.0f, blockerDepth, blockers, radius};
    const float v = poissonTaps(map, r, f, f.pcssMode.y, radius, turns, dzRange, m);
    return {gpu::snapToExtremes(v), blockerDepth, blockers, radius};
}

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
                    const gpu::ShadowViewData& view, glm::vec2 uv,
                    glm::vec4 (*stored)(glm::vec4) = nullptr) {
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

glm::vec4 vsm(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
              const gpu::ShadowViewData& view) {
    const auto taps = static_cast<uint32_t>(f.vsmParams.z);
    const glm::vec2 moments =
        f.vsmParams.w > 0.0f
            ? vsmMomentsMip(vsmMipChain(map, taps, view), map.size, probe, f.vsmParams.w)
            : glm::vec2(momentsAt(map, MOMENTS_VSM, taps, glm::vec2(0.0f), view, probe.uv));
    const float t = gpu::momentDepth(view, probe.depth);
    const float bound = gpu::chebyshevUpperBound(moments, t, f.vsmParams.x);
    return {gpu::snapToExtremes(gpu::reduceLightBleeding(bound, f.vsmParams.y)), moments, t};
}

glm::vec4 esm(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
              const gpu::ShadowViewData& view) {
    const float filtered = momentsAt(map, MOMENTS_ESM, static_cast<uint32_t>(f.esmParams.y),
                                     glm::vec2(f.esmParams.x), view, probe.uv)
                               .x;
    const float t = gpu::momentDepth(view, probe.depth);
    return {gpu::snapToExtremes(gpu::exponentialVisibility(filtered, t, f.esmParams.x)), filtered,
            t, 0.0f};
}

glm::vec4 evsm(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
               const gpu::ShadowViewData& view) {
    const glm::vec2 exponents(f.evsmParams.x, f.evsmParams.y);
    const glm::vec4 moments = momentsAt(map, MOMENTS_EVSM, f.evsmMode.y, exponents, view, probe.uv);
    const float t = gpu::momentDepth(view, probe.depth);
    const float p =
        gpu::exponentialVarianceVisibility(moments, t, exponents, f.evsmParams.z, f.evsmMode.x);
    return {gpu::snapToExtremes(gpu::reduceLightBleeding(p, f.evsmParams.w)), moments.x, moments.z,
            t};
}

glm::vec4 storedIn16Bits(glm::vec4 moments) {
    return gpu::msmStore16(moments);
}

glm::vec4 msm(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f,
              const gpu::ShadowViewData& view) {
    const bool sixteen = f.msmParams.z == 16.0f;
    glm::vec4 moments =
        momentsAt(map, MOMENTS_MSM, static_cast<uint32_t>(f.msmParams.y), glm::vec2(0.0f), view,
                  probe.uv, sixteen ? &storedIn16Bits : nullptr);
    if (sixteen)
        moments = gpu::msmLoad16(moments);
    const float d = 2.0f * gpu::momentDepth(view, probe.depth) - 1.0f;
    const float v = std::clamp(1.0f - gpu::momentOcclusion(moments, d, f.msmParams.x), 0.0f, 1.0f);
    return {gpu::snapToExtremes(v), moments.x, moments.y, d};
}

glm::vec4 evaluate(Technique technique, const ShadowMapView& map, const FilterProbe& probe,
                   const gpu::FrameData& f, const gpu::ShadowViewData& view,
                   const MarginTracker& m) {
    switch (technique) {
    case Technique::Pcss:
        return pcss(map, probe, f, view, m);
    case Technique::Pcf:
        return {pcf(map, probe, f, m), 0.0f, 0.0f, 0.0f};
    case Technique::Vsm: // `map` holds the light's depth; the moments are derived here
        return vsm(map, probe, f, view);
    case Technique::Esm:
        return esm(map, probe, f, view);
    case Technique::Evsm:
        return evsm(map, probe, f, view);
    case Technique::Savsm:
        return savsmReference(map, probe, f, view);
    case Technique::Vssm:
        return vssmReference(map, probe, f, view);
    case Technique::MsmSoft:
        return msmSoftReference(map, probe, f, view);

    case Technique::Msm:
        return msm(map, probe, f, view);
    case Technique::SecondDepth: // `map` holds the midpoints; no receiver-plane correction
        return {hard(map, probe, m, glm::vec2(0.0f)), 0.0f, 0.0f, 0.0f};
    case Technique::Sdf:
        throw InputError("sdf", "it traces a distance field: there is no shadow-map filter to "
                                "evaluate");
    case Technique::Hard:
        break;
    }
    return {hard(map, probe, m, glm::vec2(f.biasParams.x, f.biasParams.y)), 0.0f, 0.0f, 0.0f};
}

} // namespace

float ShadowMapView::texel(int i, int j) const {
    const int last = static_cast<int>(size) - 1;
    return depth[static_cast<size_t>(std::clamp(j, 0, last)) * size +
                 static_cast<size_t>(std::clamp(i, 0, last))];
}

float hardReference(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f) {
    return hard(map, probe, {}, glm::vec2(f.biasParams.x, f.biasParams.y));
}

float pcfReference(const ShadowMapView& map, const FilterProbe& probe, const gpu::FrameData& f) {
    return pcf(map, probe, f, {});
}

glm::vec4 techniqueReference(Technique technique, const ShadowMapView& map,
                             const FilterProbe& probe, const gpu::FrameData& f,
                             const gpu::ShadowViewData& view) {
    return evaluate(technique, map, probe, f, view, {});
}

float smallestComparisonMargin(Technique technique, const ShadowMapView& map,
                               const FilterProbe& probe, const gpu::FrameData& f,
                               const gpu::ShadowViewData& view) {
    float margin = 1e30f;
    evaluate(technique, map, probe, f, view, MarginTracker{&margin});
    return margin;
}

} // namespace penumbra
