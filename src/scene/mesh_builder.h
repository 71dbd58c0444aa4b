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
    // A material with a base-colour texture (its image is added to the scene).
    uint32_t texturedMaterial(const std::string& name, TextureImage image, const Texture& sampling,
                              AlphaMode mode, float alphaCutoff = 0.5f);
    // Quad through four corners in counter-clockwise order seen from its front; texture
    // coordinates run from (0, uvScale.y) at `a` to (uvScale.x, 0) at `c`.
    void quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, const glm::vec3& d,
              uint32_t material, glm::vec2 uvScale = glm::vec2(1.0f));
    // The unit cube [-1/2, 1/2]^3 under `transform` (flat-shaded, 12 triangles).
    void box(const glm::mat4& transform, uint32_t material);
    // A box of square cross-section `thickness` from `from` to `to`.
    void beam(const glm::vec3& from, const glm::vec3& to, float thickness, uint32_t material);
    void sphere(const glm::vec3& center, float radius, uint32_t material, uint32_t slices = 64,
                uint32_t stacks = 32);
    // A closed cylinder from `from` to `to`: smooth-shaded sides of `slices` facets (the
    // shading normal then differs from each facet's own, as on real assets) and flat caps.
    void tube(const glm::vec3& from, const glm::vec3& to, float radius, uint32_t material,
              uint32_t slices = 12);
    // A smooth-shaded torus around `axis` (unit) through `center`: a ring of `segments` x
    // `sides` facets, tube radius `minor` about a circle of radius `major`.
    void torus(const glm::vec3& center, const glm::vec3& axis, float major, float minor,
               uint32_t material, uint32_t segments = 32, uint32_t sides = 10);

private:
    uint32_t vertex(const glm::vec3& p, const glm::vec3& n, uint32_t material,
                    glm::vec2 uv = glm::vec2(0.0f));
    Scene& mScene;
};

} // namespace penumbra
