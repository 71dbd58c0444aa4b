#pragma once
// The taps the CPU references build their kernels from: shaders/include/receiver.glsl and
// shadow_hard.glsl transcribed operation for operation (float arithmetic, the same texel clamping
// as textureGather with clamp-to-edge), each comparison reported to a MarginTracker.
#include "frame_block.h"
#include "shadows/technique.h"

#include <glm/glm.hpp>

namespace penumbra::shadows {

// The receiver as the taps read it (receiver.glsl's Receiver, less what the CPU references do not
// use).
struct CpuReceiver {
    glm::vec2 uv;
    float depth;
    glm::vec2 gradient;
    glm::vec2 curve{0.0f}, planeRange{-1e30f, 1e30f}; // bias.mode=adaptive (FilterProbe's)
    float creaseLimit = 0.0f;
};

CpuReceiver receiverOf(const FilterProbe& probe);

// One texel's comparison with receiver-plane bias (texelTest).
float texelTest(const CpuReceiver& r, float stored, glm::vec2 texelUv, glm::vec2 dzRange,
                const MarginTracker& m);
// The 2x2 tests from texel `base`: x (i, j+1), y (i+1, j+1), z (i+1, j), w (i, j), textureGather's
// order.
glm::vec4 gatherTests(const ShadowMapView& map, glm::ivec2 base, float size, const CpuReceiver& r,
                      glm::vec2 dzRange, const MarginTracker& m);
// One bilinear comparison tap at `texelPos` (texel units); `subTexelBits` > 0: the fraction
// rounded as a texture unit with that many sub-texel bits does.
float bilinearTap(const ShadowMapView& map, glm::vec2 texelPos, float size, const CpuReceiver& r,
                  glm::vec2 dzRange, const MarginTracker& m, uint32_t subTexelBits = 0);
// An n x n grid of bilinear taps (pcfGrid).
float pcfGrid(const ShadowMapView& map, const CpuReceiver& r, uint32_t filterKind, int n,
              float sigma, glm::vec2 dzRange, const MarginTracker& m);
glm::vec2 poissonPoint(const gpu::FrameData& f, uint32_t i);
// n bilinear taps on the frame's Poisson disk scaled to `radius` texels, rotated by `turns`.
float poissonTaps(const ShadowMapView& map, const CpuReceiver& r, const gpu::FrameData& f,
                  uint32_t n, float radius, float turns, glm::vec2 dzRange, const MarginTracker& m);
// The nearest texel's test (shadowHard).
float hardTest(const ShadowMapView& map, const FilterProbe& probe, const MarginTracker& m,
               glm::vec2 dzRange);

} // namespace penumbra::shadows
