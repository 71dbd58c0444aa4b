#include "report/camera_path.h"

#include <glm/gtc/matrix_transform.hpp>

#include <iterator>

namespace penumbra {

bool cameraPathFromName(std::string_view name, CameraPath& path) {
    for (size_t i = 0; i < std::size(kCameraPathNames); ++i)
        if (name == kCameraPathNames[i]) {
            path = static_cast<CameraPath>(i);
            return true;
        }
    return false;
}

std::vector<PathFrame> pathFrames(CameraPath path, const Camera& camera,
                                  const std::vector<Light>& lights, uint32_t frames,
                                  float dollyStep) {
    std::vector<PathFrame> out;
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    for (uint32_t t = 0; t < frames; ++t) {
        PathFrame f{.camera = camera, .lights = lights};
        const auto k = static_cast<float>(t);
        switch (path) {
        case CameraPath::Dolly: {
            const glm::vec3 forward = glm::normalize(camera.target - camera.position);
            f.camera.position += forward * (k * dollyStep);
            f.camera.target += forward * (k * dollyStep);
            break;
        }
        case CameraPath::Orbit: {
            const glm::mat4 turn =
                glm::rotate(glm::mat4(1.0f), glm::radians(k * kOrbitDegreesPerFrame), up);
            f.camera.position =
                camera.target + glm::vec3(turn * glm::vec4(camera.position - camera.target, 0.0f));
            break;
        }
        case CameraPath::Sun: {
            const glm::mat4 turn =
                glm::rotate(glm::mat4(1.0f), glm::radians(k * kSunDegreesPerFrame), up);
            for (Light& l : f.lights)
                if (l.type == LightType::Directional)
                    l.direction = glm::normalize(glm::vec3(turn * glm::vec4(l.direction, 0.0f)));
            break;
        }
        }
        out.push_back(std::move(f));
    }
    return out;
}

} // namespace penumbra
