// builtin:tree — a tree of BLEND leaves (docs/translucency.md), as real assets' foliage is drawn:
// an opaque trunk and branches under a crown of leaf cards whose texture's alpha is their
// coverage (alphaMode BLEND), each leaf letting a little light through where it covers (alpha
// kTreeLeafAlpha) and all of it past its edge. A ray through the crown crosses several leaves,
// so the ground's light is a product of many partial coverages: grey, since a BLEND surface
// without transmission keeps every channel alike.
#include "scene/builtin_scenes.h"

#include "scene/mesh_builder.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::builtin {
namespace {

// One leaf filling a card: an ellipse along the card's diagonal, anti-aliased (alpha is the
// covered fraction, about), kTreeLeafAlpha inside, clear outside.
TextureImage leafCardImage() {
    constexpr uint32_t kSize = kTreeLeafTextureSize;
    TextureImage image{.name = "leaf", .width = kSize, .height = kSize};
    image.rgba.assign(size_t{kSize} * kSize * 4, 0);
    const float n = static_cast<float>(kSize), a = 0.62f * n, b = 0.22f * n;
    const float c = std::cos(glm::quarter_pi<float>()), s = std::sin(glm::quarter_pi<float>());
    for (uint32_t py = 0; py < kSize; ++py)
        for (uint32_t px = 0; px < kSize; ++px) {
            const float x = static_cast<float>(px) + 0.5f - 0.5f * n;
            const float y = static_cast<float>(py) + 0.5f - 0.5f * n;
            const float u = (c * x + s * y) / a, v = (-s * x + c * y) / b;
            const float coverage = leafCoverage(u, v, b);
            uint8_t* p = &image.rgba[(size_t{py} * kSize + px) * 4];
            p[0] = 70, p[1] = 140, p[2] = 45; // sRGB
            p[3] = static_cast<uint8_t>(std::lround(coverage * kTreeLeafAlpha * 255.0f));
        }
    return image;
}

} // namespace

Scene tree() {
    Scene scene;
    scene.name = "tree";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.68f, 0.6f});
    const float g = kTreeGroundHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);

    const uint32_t bark = mb.material("bark", {0.35f, 0.25f, 0.17f});
    const glm::vec3 top = kTreeCrownCentre - glm::vec3(0.0f, 0.4f * kTreeCrownRadii.y, 0.0f);
    mb.tube({0.0f, 0.0f, 0.0f}, top, 0.16f, bark);
    SceneRandom random{20261207u};
    for (int k = 0; k < 5; ++k) { // branches up and out into the crown
        const float angle = glm::two_pi<float>() * (static_cast<float>(k) + random.next()) / 5.0f;
        const glm::vec3 tip =
            kTreeCrownCentre + glm::vec3(0.6f * kTreeCrownRadii.x * std::cos(angle),
                                         0.2f * kTreeCrownRadii.y,
                                         0.6f * kTreeCrownRadii.z * std::sin(angle));
        mb.tube(top, tip, 0.05f, bark, 6);
    }

    const uint32_t leaf = mb.texturedMaterial(
        "leaf", leafCardImage(),
        {.wrapS = TextureWrap::ClampToEdge, .wrapT = TextureWrap::ClampToEdge}, AlphaMode::Blend);
    for (int placed = 0; placed < kTreeLeaves;) {
        // A centre in the crown's ellipsoid (by rejection), a facing anywhere. One draw per
        // statement: the order a call's arguments are evaluated in differs between compilers.
        glm::vec3 r, facing;
        for (int k = 0; k < 3; ++k)
            r[k] = 2.0f * random.next() - 1.0f;
        for (int k = 0; k < 3; ++k)
            facing[k] = 2.0f * random.next() - 1.0f;
        if (glm::dot(r, r) > 1.0f || glm::dot(facing, facing) < 0.01f)
            continue;
        const glm::vec3 centre = kTreeCrownCentre + r * kTreeCrownRadii;
        const glm::vec3 n = glm::normalize(facing);
        const glm::vec3 helper = std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 u = 0.5f * kTreeLeafSize * glm::normalize(glm::cross(helper, n));
        const glm::vec3 v = glm::cross(n, u);
        mb.quad(centre - u - v, centre + u - v, centre + u + v, centre - u + v, leaf);
        ++placed;
    }

    scene.lights.push_back(sun());
    scene.lights.back().direction = glm::normalize(kTreeSunDirection);
    scene.cameras.push_back(mainCamera({4.5f, 2.2f, 6.5f}, {0.8f, 1.2f, 0.3f}, 0.9f));
    return scene;
}

} // namespace penumbra::builtin
