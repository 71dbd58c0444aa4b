#pragma once
// The short paths `compare --camera-path` renders to measure shimmer (src/report/shimmer.h):
// `dolly` moves the camera forward by a fraction of a shadow-map texel a frame, `orbit` turns it
// slowly about its target, `sun` turns every directional light by 0.05 degrees a frame about the
// world's up axis (the case engines suffer most).
#include "penumbra/scene.h"

#include <string_view>
#include <vector>

namespace penumbra {

enum class CameraPath { Dolly, Orbit, Sun };
inline constexpr const char* kCameraPathNames[] = {"dolly", "orbit", "sun"};
// false for an unknown name.
bool cameraPathFromName(std::string_view name, CameraPath& path);

inline constexpr float kOrbitDegreesPerFrame = 0.1f;
inline constexpr float kSunDegreesPerFrame = 0.05f;

struct PathFrame {
    Camera camera;
    std::vector<Light> lights;
};

// `frames` frames from `camera` and `lights` (frame 0 is them unchanged). `dollyStep`: how far
// the dolly moves a frame, world units (the caller picks a fraction of a texel).
std::vector<PathFrame> pathFrames(CameraPath path, const Camera& camera,
                                  const std::vector<Light>& lights, uint32_t frames,
                                  float dollyStep);

} // namespace penumbra
