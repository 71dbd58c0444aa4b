#pragma once
// The viewer's camera: orbit (drag with the left button around the target, wheel to dolly) or
// fly (WASD, Q/E down/up, Shift faster, right button drag to look). Either starts from the
// scene's camera; the scene's cameras can be taken over at any time.
#include "penumbra/scene.h"

#include <glm/glm.hpp>

namespace penumbra::viewer {

enum class CameraMode { Orbit, Fly };

// What moved since the last frame: mouse motion while a button is held, the wheel, the keys.
struct CameraInput {
    glm::vec2 dragLeft{0.0f}, dragRight{0.0f}; // pixels
    float wheel = 0.0f;                        // notches, positive away from the user
    glm::vec3 move{0.0f};                      // fly: x right, y up, z forward, each -1..1
    bool fast = false;
    float seconds = 0.0f; // since the last frame
};

class CameraControl {
public:
    // `sceneSize`: the scene's bounding-box diagonal (sets the speeds).
    CameraControl(const Camera& start, float sceneSize);
    void reset(const Camera& camera);
    // Applies one frame's input; returns whether the camera changed.
    bool update(const CameraInput& input, CameraMode mode);
    const Camera& camera() const { return mCamera; }

private:
    Camera mCamera;
    float mSceneSize;
};

} // namespace penumbra::viewer
