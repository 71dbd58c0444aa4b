#pragma once
// Shimmer: how much a technique's visibility changes from frame to frame where the truth does
// not (issue 11), measured on the same pixels of the same frame so that nothing but the shadow
// changes:
//  - a moving camera (dolly, orbit): the true visibility of a world point never changes, so
//    every change is an artifact. Frame t is rendered twice with its own camera and G-buffer:
//    once with the shadow views fitted for frame t, once with those of frame t - 1 (cascades
//    follow the camera; a map over the whole scene does not). Shimmer is the mean |v - v'|:
//    how far each visible point's shadow moved when the views did (crawling edges).
//  - a moving light (sun): the truth changes too; with the camera still, shimmer is the mean of
//    |(v_t - v_{t-1}) - (truth_t - truth_{t-1})| per pixel.
// Pixels count when the light reaches them in both frames (the metrics' light mask).
#include <cstdint>
#include <span>

namespace penumbra {

// Two visibility images of one view (rows top to bottom; NaN = background), and, for a moving
// light, the truths of both frames (empty for a moving camera).
struct ShimmerPair {
    std::span<const float> visibility, previous;
    std::span<const float> truth, previousTruth;
    std::span<const uint8_t> mask, previousMask; // 1 = the light reaches the pixel
};

struct ShimmerResult {
    double shimmer = 0.0; // mean over the counted pixels of every pair
    uint64_t pixels = 0;
};

// Spans of one pair that differ in size are a programmer error.
ShimmerResult measureShimmer(std::span<const ShimmerPair> pairs);

// Flicker (issue 59, docs/cli.md): the mean frame-to-frame change of the error,
// |(v_t - truth_t) - (v_{t-1} - truth_{t-1})|, over the pixels whose truth did not change
// (|truth_t - truth_{t-1}| <= kUnchangedTruth) and which the light reaches in both frames: what
// a technique adds from frame to frame where nothing it should show moved. Every pair needs its
// truths.
inline constexpr double kUnchangedTruth = 1e-6;
ShimmerResult measureFlicker(std::span<const ShimmerPair> pairs);

} // namespace penumbra
