#include "camera_control.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::viewer {
namespace {

constexpr float kRadiansPerPixel = 0.005f;

// `v` turned by `yaw` about the world's up and `pitch` about the view's right, keeping it away
// from the poles (a view straight up or down has no right).
glm::vec3 turn(glm::vec3 v, glm::vec3 up, float yaw, float pitch) {
    const float length = glm::length(v);
    glm::vec3 d = v / length;
    const float cy = std::cos(yaw), sy = std::sin(yaw);
    // Rodrigues' rotation about `up`.
    d = d * cy + glm::cross(up, d) * sy + up * glm::dot(up, d) * (1.0f - cy);
    const float elevation = std::asin(std::clamp(glm::dot(d, up), -1.0f, 1.0f));
    const float wanted = std::clamp(elevation + pitch, -1.5f, 1.5f);
    const glm::vec3 flat = d - up * glm::dot(d, up);
    const glm::vec3 horizontal =
        glm::length(flat) > 1e-6f ? glm::normalize(flat) : glm::vec3(1, 0, 0);
    return length * (horizontal * std::cos(wanted) + up * std::sin(wanted));
}

} // namespace

CameraControl::CameraControl(const Camera& start, float sceneSize)
    : mCamera(start), mSceneSize(std::max(sceneSize, 1e-3f)) {}

void CameraControl::reset(const Camera& camera) {
    mCamera = camera;
}

bool CameraControl::update(const CameraInput& in, CameraMode mode) {
    Camera& c = mCamera;
    const glm::vec3 up = glm::normalize(c.up);
    const Camera before = c;
    if (mode == CameraMode::Orbit) {
        const glm::vec2 drag = in.dragLeft * kRadiansPerPixel;
        if (drag != glm::vec2(0.0f))
            c.position = c.target + turn(c.position - c.target, up, -drag.x, drag.y);
        if (in.wheel != 0.0f) {
            const float scale = std::pow(0.9f, in.wheel);
            const glm::vec3 offset = (c.position - c.target) * scale;
            if (glm::length(offset) > 1e-4f * mSceneSize)
                c.position = c.target + offset;
        }
    } else {
        const glm::vec2 look = in.dragRight * kRadiansPerPixel;
        glm::vec3 forward = glm::normalize(c.target - c.position);
        if (look != glm::vec2(0.0f))
            forward = glm::normalize(turn(forward, up, -look.x, -look.y));
        const glm::vec3 right = glm::normalize(glm::cross(forward, up));
        const float speed = mSceneSize * 0.25f * (in.fast ? 4.0f : 1.0f) * in.seconds;
        const glm::vec3 step = (right * in.move.x + up * in.move.y + forward * in.move.z) * speed +
                               forward * in.wheel * 0.05f * mSceneSize;
        c.position += step;
        const float distance = std::max(glm::length(before.target - before.position), 1e-3f);
        c.target = c.position + forward * distance;
    }
    return c.position != before.position || c.target != before.target;
}

} // namespace penumbra::viewer
