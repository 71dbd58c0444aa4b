#pragma once
// START:END:STEP in seconds: `compare --timeline`'s frames and a sweep plan's `times`, parsed
// and refused in one place, so that both read a range alike and the unit tests hold its bounds.
#include <cstddef>
#include <string_view>

namespace penumbra {

struct Timeline {
    double start = 0.0, end = 0.0, step = 0.0;
    size_t frames = 0; // start, start + step, ... up to end (within a millionth of a step)
    // start + frame * step to 12 significant digits: 0.1 * 3 is 0.3, not 0.30000000000000004.
    double at(size_t frame) const;
};

inline constexpr size_t kMaxTimelineFrames = 10000;

// "START:END:STEP" in seconds: START >= 0, END >= START, STEP > 0, at most kMaxTimelineFrames
// frames; InputError("--timeline", ...) otherwise.
Timeline parseTimeline(std::string_view text);

} // namespace penumbra
