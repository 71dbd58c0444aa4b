#pragma once
// Shimmer: how much a technique's visibility changes from frame to frame where the truth does
// not (issue 11). For a camera path (dolly, orbit) the true visibility of a world point never
// changes, so any change is an artifact: shimmer is the mean |v_t(p) - v_{t-1}(p)| over pixels
// whose world position p, reprojected into the previous frame, lands on the same surface there.
// For a moving light the truth changes too, and shimmer is the mean of
// |(v_t - v_{t-1}) - (truth_t - truth_{t-1})| on the same pixels. Noise fixed to the screen
// counts as shimmer: that is what a user sees.
#include <glm/glm.hpp>

#include <cstdint>
#include <span>

namespace penumbra {

// One frame of a path, as rendered: rows top to bottom, camera conventions of
// src/core/projection.h (reverse-Z, y flipped).
struct ShimmerFrame {
    uint32_t width = 0, height = 0;
    std::span<const float> visibility; // per pixel; NaN = background
    std::span<const float> truth;      // per pixel, for a moving light; empty for camera paths
    std::span<const float> position;   // xyz per pixel, world; NaN = background
    std::span<const uint8_t> mask;     // 1 = counted (the light reaches the pixel)
    glm::mat4 viewProj{1.0f};          // the camera's world -> clip
    glm::vec3 cameraPosition{0.0f};
    float pixelAngle = 0.0f; // a pixel's world size at unit distance (perspective); 0 with
    float pixelSize = 0.0f;  // an orthographic camera, whose pixels are pixelSize wide
};

struct ShimmerResult {
    double shimmer = 0.0; // mean over the matched pixels of every consecutive pair
    uint64_t matched = 0; // pixels that found the same surface in the previous frame
    uint64_t counted = 0; // counted, non-background pixels of frames 1..N-1
};

// A pixel of frame t matches when its position, projected by frame t-1's camera, falls where the
// four nearest pixel centres of frame t-1 are all counted surface points, and their position,
// interpolated bilinearly at that point, lies within 1% of the pixel's footprint of it (the same
// surface, not an edge or another object); the previous visibility (and truth) is interpolated
// the same way. Frames must share one size (a programmer error otherwise).
ShimmerResult measureShimmer(std::span<const ShimmerFrame> frames);

} // namespace penumbra
