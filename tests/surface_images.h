#pragma once
// Images of surfaces made in code, for the CPU mirrors of the screen-space passes that read the
// G-buffer's positions and normals (the visibility filter, checkerboard tracing's fill).
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace penumbra::test {

// position (NaN: the background) and normal, xyz a pixel, and visibility, row by row.
struct SurfaceImage {
    std::vector<float> position, normal, visibility;
};

inline SurfaceImage surfaceImage(uint32_t width, uint32_t height,
                                 const std::function<glm::vec3(int, int)>& position,
                                 const std::function<glm::vec3(int, int)>& normal,
                                 const std::function<float(int, int)>& visibility) {
    SurfaceImage s;
    for (int y = 0; y < int(height); ++y)
        for (int x = 0; x < int(width); ++x) {
            const glm::vec3 p = position(x, y), n = normal(x, y);
            s.position.insert(s.position.end(), {p.x, p.y, p.z});
            s.normal.insert(s.normal.end(), {n.x, n.y, n.z});
            s.visibility.push_back(visibility(x, y));
        }
    return s;
}

// The plane z = 0, pixels 0.1 apart, and its normal.
inline glm::vec3 onPlane(int x, int y) {
    return {0.1f * float(x), 0.1f * float(y), 0.0f};
}
inline glm::vec3 up(int, int) {
    return {0.0f, 0.0f, 1.0f};
}

} // namespace penumbra::test
