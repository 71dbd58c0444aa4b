// The filter kernels' scalar maths, compiled as GLSL by the shaders and as C++ by the CPU
// references (src/shadows/*.cpp), so both run the same code: the bilinear comparison tap's
// weights, box and Gaussian footprints, Poisson rotations, a sun's cascades' kernel sizes.
// A bug written here reaches both sides at once: the parity tests cannot see it, the
// closed-form tests (tests/test_filter_closed_forms.cpp) and the ground truth can.
// clang-format off
#ifndef PENUMBRA_KERNELS_H
#define PENUMBRA_KERNELS_H
#include "shared_prelude.h"

// pcf.filter and pcf.rotation / pcss.rotation: indices of their choices in the registry.
#define FILTER_BILINEAR 0u
#define FILTER_HARDWARE 1u
#define FILTER_BOX 2u
#define FILTER_GAUSSIAN 3u
#define FILTER_POISSON 4u
#define ROTATION_NONE 0u
#define ROTATION_RANDOM 1u
#define ROTATION_IGN 2u
#define POISSON_MAX_SAMPLES 64u

PENUMBRA_GPU_BEGIN

#define PCF_MAX_SIZE 15

// A bilinear comparison tap from its four tests in textureGather order (x (i, j+1), y (i+1, j+1),
// z (i+1, j), w (i, j)) and the tap's sub-texel fraction.
SHARED float bilinearMix(vec4 t, vec2 f) {
    return mix(mix(t.w, t.z, f.x), mix(t.x, t.y, f.x), f.y);
}

// Texel weights of an n-tap kernel (box: 1/n; Gaussian with sigma, normalised) after bilinear
// taps with sub-texel fraction f: texel k of the (n+1)-wide footprint gets
// c(k) = g(k)(1 - f) + g(k-1) f.
SHARED void footprintWeights(uint filterKind, int n, float sigma, float f,
                             OUT_ARRAY(float, c, PCF_MAX_SIZE + 1)) {
    float g[PCF_MAX_SIZE];
    float h = 0.5f * float(n - 1), sum = 0.0f;
    for (int i = 0; i < n; ++i) {
        float x = float(i) - h;
        g[i] = filterKind == FILTER_GAUSSIAN ? exp(-0.5f * x * x / (sigma * sigma)) : 1.0f;
        sum += g[i];
    }
    for (int k = 0; k <= n; ++k)
        c[k] = ((k < n ? g[k] : 0.0f) * (1.0f - f) + (k > 0 ? g[k - 1] : 0.0f) * f) / sum;
}

SHARED uint hashU32(uint v) { // lowbias32, a public-domain integer hash
    v ^= v >> 16u;
    v *= 0x7feb352du;
    v ^= v >> 15u;
    v *= 0x846ca68bu;
    v ^= v >> 16u;
    return v;
}

// Per-pixel rotation of a Poisson disk, in turns [0, 1): none, a hash, or interleaved gradient
// noise [Jimenez 2014]. PRECISE: a fused multiply-add moves IGN's inner fraction by an ulp of ~70,
// the turn by 4e-4 after the factor 53 (a GPU's taps moved by 0.01 texel against the CPU's).
SHARED float rotationTurns(uint rotation, uvec2 pixel) {
    if (rotation == ROTATION_RANDOM)
        return float(hashU32(pixel.x * 0x9E3779B9u ^ hashU32(pixel.y))) * (1.0f / 4294967296.0f);
    if (rotation == ROTATION_IGN) {
        PRECISE float inner = 0.06711056f * float(pixel.x) + 0.00583715f * float(pixel.y);
        PRECISE float scaled = 52.9829189f * fract(inner);
        return fract(scaled);
    }
    return 0.0f;
}

// A frame's turn of every per-pixel rotation (pcf, pcss, smrt, contact; the `temporal` layer's
// frames, FrameData::motion.y), in turns: frame i
// turns by i times the golden ratio's fraction, in 32-bit fixed point (exact, whatever i), so
// that a pixel's rotations over frames spread as evenly as a sequence can (the R1 sequence).
// Frame 0 turns by nothing: a technique without the layer draws what it always drew.
SHARED float frameTurn(uint frameIndex) {
    return float((frameIndex * 0x9E3779B9u) >> 8u) * (1.0f / 16777216.0f);
}
SHARED float turnedByFrame(float turns, uint frameIndex) {
    return frameIndex == 0u ? turns : fract(turns + frameTurn(frameIndex));
}

// (cos, sin) of `turns` of a full turn from adds and multiplies alone: Vulkan allows sin and cos an
// absolute error of 2^-11, which moves a tap 3 texels out by 0.003 texel, while these operations
// are correctly rounded on every device. The quadrant is exact; within it, Taylor series of
// x = (pi / 2) f to x^11 and x^12 (error under 6e-8; the pattern needs agreement, not accuracy).
SHARED vec2 turnCosSin(float turns) {
    PRECISE float q = 4.0f * fract(turns);
    float quadrant = floor(q);
    PRECISE float x = 1.57079632679f * (q - quadrant);
    PRECISE float x2 = x * x;
    PRECISE float s = x * (1.0f + x2 * (-1.0f / 6.0f + x2 * (1.0f / 120.0f + x2 * (-1.0f / 5040.0f +
                      x2 * (1.0f / 362880.0f + x2 * (-1.0f / 39916800.0f))))));
    PRECISE float c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24.0f + x2 * (-1.0f / 720.0f +
                      x2 * (1.0f / 40320.0f + x2 * (-1.0f / 3628800.0f + x2 * (1.0f / 479001600.0f))))));
    if (quadrant == 0.0f) return vec2(c, s);
    if (quadrant == 1.0f) return vec2(-s, c);
    if (quadrant == 2.0f) return vec2(-c, -s);
    return vec2(s, -c);
}

// `d` rotated by `turns` of a full turn, scaled by `radius`.
SHARED vec2 rotatedOffset(vec2 d, float turns, float radius) {
    vec2 cs = turnCosSin(turns);
    PRECISE vec2 rotated = vec2(cs.x * d.x - cs.y * d.y, cs.y * d.x + cs.x * d.y);
    PRECISE vec2 scaled = radius * rotated;
    return scaled;
}

// An n x n kernel (n odd) set in texels of a sun's first cascade, in a cascade whose texels are
// 1/scale times as wide (scale <= 1): the odd size nearest n x scale, at least 1, so the kernel
// keeps its world size.
SHARED int scaledKernelSize(uint n, float scale) {
    if (scale >= 1.0f) return int(n);
    int k = 2 * int(floor(0.5f * (float(n) * scale - 1.0f) + 0.5f)) + 1;
    return k < 1 ? 1 : k;
}

// Weight of tap k (-(n-1)/2 .. (n-1)/2) of the n-tap Gaussian blur, before normalising: sigma
// = n / 6, so the taps reach three sigmas on either side.
SHARED float gaussianTap(int k, int n) {
    float sigma = max(float(n) / 6.0f, 0.3f);
    return exp(-0.5f * float(k * k) / (sigma * sigma));
}

// Weighted sums of exact 0/1 tests land within float round-off of 0 or 1 when every test agrees;
// fully lit must read exactly 1 (and fully shadowed 0), so round-off snaps.
SHARED float snapToExtremes(float v) { return v >= 0.99999f ? 1.0f : (v <= 0.00001f ? 0.0f : v); }

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
// The names of pcf.filter and pcf.rotation / pcss.rotation in the order of the values above:
// the registry's choice lists are these arrays, so a name's index is the value the shaders
// compare with.
inline constexpr const char* kFilterChoices[] = {"bilinear", "hardware", "box", "gaussian",
                                                 "poisson"};
inline constexpr const char* kRotationChoices[] = {"none", "random", "ign"};
static_assert(FILTER_BILINEAR == 0 && FILTER_HARDWARE == 1 && FILTER_BOX == 2 &&
              FILTER_GAUSSIAN == 3 && FILTER_POISSON == 4 && std::size(kFilterChoices) == 5);
static_assert(ROTATION_NONE == 0 && ROTATION_RANDOM == 1 && ROTATION_IGN == 2 &&
              std::size(kRotationChoices) == 3);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
