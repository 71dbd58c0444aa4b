#pragma once
// Whether a segment meets an axis-aligned box: the closed forms of the translucent scenes' tests
// ask which casters a light ray crosses.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace penumbra::test {

// Whether the segment p + t d, 0 < t < length, meets the box [lo, hi] (none when lo > hi in
// an axis: a box shrunk to nothing).
inline bool segmentMeetsBox(glm::dvec3 p, glm::dvec3 d, double length, glm::dvec3 lo,
                            glm::dvec3 hi) {
    if (glm::any(glm::greaterThan(lo, hi)))
        return false;
    double enter = 0.0, leave = length;
    for (int a = 0; a < 3; ++a) {
        if (std::abs(d[a]) < 1e-12) {
            if (p[a] < lo[a] || p[a] > hi[a])
                return false;
            continue;
        }
        double t0 = (lo[a] - p[a]) / d[a], t1 = (hi[a] - p[a]) / d[a];
        if (t0 > t1)
            std::swap(t0, t1);
        enter = std::max(enter, t0), leave = std::min(leave, t1);
    }
    return enter <= leave;
}

} // namespace penumbra::test
