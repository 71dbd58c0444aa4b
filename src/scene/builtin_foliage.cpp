// builtin:foliage — alpha-tested casters (glTF alphaMode MASK): a pergola whose roof is a
// tiled leaf texture, crossed-quad bushes and a lattice trellis. Their shadows are dappled:
// the light passes through the texture's holes, in the shadow map and in the ground truth.
#include "scene/builtin_scenes.h"
#include "scene/mesh_builder.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::builtin {

TextureImage leafImage(uint32_t seed, int count) {
    constexpr uint32_t kSize = kLeafTextureSize;
    TextureImage image{.name = "leaves", .width = kSize, .height = kSize};
    image.rgba.assign(size_t{kSize} * kSize * 4, 0);
    SceneRandom random{seed};
    for (int leaf = 0; leaf < count; ++leaf) {
        const float cx = random.next() * kSize, cy = random.next() * kSize;
        const float angle = random.next() * glm::pi<float>();
        const float a = 9.0f + 9.0f * random.next(), b = 3.5f + 3.5f * random.next();
        // One statement per draw: argument evaluation order is unspecified (gcc and clang
        // differ), and the scene must be the same from every compiler.
        const float blue = 0.06f + 0.08f * random.next();
        const float green = 0.35f + 0.3f * random.next();
        const float red = 0.10f + 0.15f * random.next();
        const glm::vec3 leafColor(red, green, blue);
        const float c = std::cos(angle), s = std::sin(angle);
        const int reach = static_cast<int>(std::ceil(a)) + 1;
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx) {
                const int px = static_cast<int>(cx) + dx, py = static_cast<int>(cy) + dy;
                const float x = static_cast<float>(px) + 0.5f - cx;
                const float y = static_cast<float>(py) + 0.5f - cy;
                const float u = (c * x + s * y) / a, v = (-s * x + c * y) / b;
                const float coverage = leafCoverage(u, v, b);
                const size_t i = (size_t((py + int(kSize)) % int(kSize)) * kSize +
                                  size_t((px + int(kSize)) % int(kSize))) *
                                 4;
                const auto alpha = static_cast<uint8_t>(std::lround(coverage * 255.0f));
                if (alpha <= image.rgba[i + 3])
                    continue;
                for (int k = 0; k < 3; ++k) // sRGB-encode the linear colour
                    image.rgba[i + k] = static_cast<uint8_t>(
                        std::lround(255.0f * std::pow(leafColor[k], 1.0f / 2.2f)));
                image.rgba[i + 3] = alpha;
            }
    }
    return image;
}

namespace {

// A square lattice: bars kLatticeBar texels wide every kLatticePeriod, open between.
TextureImage latticeImage() {
    constexpr uint32_t kSize = kLatticeTextureSize;
    TextureImage image{.name = "lattice", .width = kSize, .height = kSize};
    image.rgba.resize(size_t{kSize} * kSize * 4);
    for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
            const bool bar = x % kLatticePeriod < kLatticeBar || y % kLatticePeriod < kLatticeBar;
            uint8_t* p = &image.rgba[(size_t{y} * kSize + x) * 4];
            p[0] = 200, p[1] = 180, p[2] = 150, p[3] = bar ? 255 : 0;
        }
    return image;
}

} // namespace

Scene foliage() {
    Scene scene;
    scene.name = "foliage";
    MeshBuilder mb(scene);
    const uint32_t ground = mb.material("ground", {0.7f, 0.7f, 0.68f});
    const uint32_t wood = mb.material("wood", {0.6f, 0.45f, 0.25f});
    const uint32_t leaves =
        mb.texturedMaterial("leaves", leafImage(), {}, AlphaMode::Mask, kFoliageAlphaCutoff);
    const uint32_t lattice = mb.texturedMaterial(
        "lattice", latticeImage(),
        {.wrapS = TextureWrap::ClampToEdge, .wrapT = TextureWrap::ClampToEdge, .nearest = true},
        AlphaMode::Mask, kFoliageAlphaCutoff);
    const float g = kGroundHalfSize;
    mb.quad({-g, 0, g}, {g, 0, g}, {g, 0, -g}, {-g, 0, -g}, ground);

    // Pergola: four posts and a roof of leaves, the texture tiled kCanopyTiles times.
    const glm::vec3 lo = kCanopyMin, hi = kCanopyMax;
    for (const glm::vec2 post : {glm::vec2(lo.x, lo.z), glm::vec2(hi.x, lo.z),
                                 glm::vec2(hi.x, hi.z), glm::vec2(lo.x, hi.z)})
        mb.beam({post.x, 0.0f, post.y}, {post.x, lo.y, post.y}, 0.12f, wood);
    mb.quad({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, leaves,
            kCanopyTiles);

    // Bushes: two crossed vertical quads each.
    for (const glm::vec3 bush : {glm::vec3(3.2f, 0.0f, 1.8f), glm::vec3(-5.6f, 0.0f, 2.2f)}) {
        const float r = 1.0f, h = 1.8f;
        mb.quad(bush + glm::vec3(-r, 0, 0), bush + glm::vec3(r, 0, 0), bush + glm::vec3(r, h, 0),
                bush + glm::vec3(-r, h, 0), leaves, {1.0f, 0.9f});
        mb.quad(bush + glm::vec3(0, 0, r), bush + glm::vec3(0, 0, -r), bush + glm::vec3(0, h, -r),
                bush + glm::vec3(0, h, r), leaves, {1.0f, 0.9f});
    }

    // Trellis: one lattice quad, the texture clamped (stretched once over it).
    const glm::vec3 t0 = kTrellisMin, t1 = kTrellisMax;
    mb.quad({t0.x, 0.0f, t0.z}, {t1.x, 0.0f, t0.z}, {t1.x, t1.y, t0.z}, {t0.x, t1.y, t0.z},
            lattice);

    scene.lights.push_back(sun());
    scene.cameras.push_back(mainCamera({0.0f, 8.0f, 11.5f}, {-0.5f, 0.8f, -1.2f}, 0.8f));
    return scene;
}

} // namespace penumbra::builtin
