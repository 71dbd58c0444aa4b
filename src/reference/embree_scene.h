#pragma once
// An Embree device and scene built from exactly the triangles the rasterizer draws. Embree
// reports errors through a callback; they surface here as std::runtime_error("embree: ..."),
// never as a crash or a silent wrong answer.
#include "penumbra/scene.h"

#include <embree3/rtcore.h>
#include <glm/glm.hpp>

#include <string>

namespace penumbra {

class EmbreeScene {
public:
    EmbreeScene(const Scene& scene, const std::string& config);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    // Whether anything blocks the open segment origin + t dir, 0 < t < tfar.
    bool occluded(const glm::vec3& origin, const glm::vec3& dir, float tfar) const;
    size_t triangles() const { return mTriangles; }

private:
    void throwIfFailed(const char* what) const;
    RTCDevice mDevice = nullptr;
    RTCScene mScene = nullptr;
    size_t mTriangles = 0;
    std::string mError; // first message from Embree's error callback
};

} // namespace penumbra
