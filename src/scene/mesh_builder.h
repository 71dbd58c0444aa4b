#pragma once
// Appends world-space primitives to a Scene. Closed shapes (boxes, spheres) are watertight;
// quads are open, single-sided surfaces (the renderer draws both sides).
#include "penumbra/scene.h"

#include <glm/glm.hpp>

namespace penumbra {

class MeshBuilder {
public:
    explicit MeshBuilder(Scene& scene) : mScene(scene) {}

    uint32_t material(const std::string& name, const glm::vec3& linearColor);
    // Quad through four corners in counter-clockwise order seen from its front.
    void quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
              uint32_t material);
    // The unit cube [-1/2, 1/2]^3 under `transform` (flat-shaded, 12 triangles).
    void box(const glm::mat4& transform, uint32_t material);
    // A box of square cross-section `thickness` from `from` to `to`.
    void beam(const glm::vec3& from, const glm::vec3& to, float thickness, uint32_t material);
    void sphere(const glm::vec3& center, float radius, uint32_t material, uint32_t slices = 64,
                uint32_t stacks = 32);

private:
    uint32_t vertex(const glm::vec3& p, const glm::vec3& n, uint32_t material);
    Scene& mScene;
};

} // namespace penumbra
