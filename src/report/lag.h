#pragma once
// Lag and pop-in (issue 59, docs/cli.md "Temporal metrics"): how much worse a technique is while
// things move than at rest on the same pose. A frame at rest is the pose rendered from scratch
// after warm-up, the technique's steady state; a frame in motion is the same pose drawn as the
// next frame of a renderer that drew every frame before it, with no warm-up. A technique that
// keeps nothing between frames draws both alike; one that keeps state (a virtual map's cached
// pages, asked for a frame ahead; a temporal history) shows its lag in the difference.
#include <cstddef>
#include <vector>

namespace penumbra {

// A frame in motion counts as lagging when its error exceeds the one at rest by more than this
// share of it: "back within 10% of the steady state".
inline constexpr double kLagTolerance = 0.10;

struct Lag {
    double popIn = 0.0;       // max over frames of (moving - rest): the worst excess error
    double popInRatio = 1.0;  // max over frames whose rest error is > 0 of moving / rest
    size_t lagFrames = 0;     // the longest run of consecutive lagging frames
    size_t laggingFrames = 0; // lagging frames in all
};

// `rest[k]` and `moving[k]`: one error (RMSE) per frame, the same count. Frame 0 is where the
// motion starts: both renderers start there at rest, so it is measured like the others.
Lag measureLag(const std::vector<double>& rest, const std::vector<double>& moving);

} // namespace penumbra
