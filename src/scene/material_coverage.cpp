// Alpha coverage on the CPU, the same test the shadow pass and the G-buffer make on the GPU:
// coverage = baseColor.a x vertex alpha x texture alpha, the texture read at full resolution
// with the sampler's wrap modes and magnification filter (texel centres at (i + 1/2) / size).
#include "penumbra/scene.h"

#include <algorithm>
#include <cmath>

namespace penumbra {
namespace {

// Texel index along one axis for wrap mode `wrap` (i may be any integer).
uint32_t wrapIndex(int64_t i, uint32_t size, TextureWrap wrap) {
    const auto n = static_cast<int64_t>(size);
    switch (wrap) {
    case TextureWrap::ClampToEdge:
        return static_cast<uint32_t>(std::clamp<int64_t>(i, 0, n - 1));
    case TextureWrap::MirroredRepeat: {
        const int64_t period = 2 * n;
        int64_t m = ((i % period) + period) % period;
        return static_cast<uint32_t>(m < n ? m : period - 1 - m);
    }
    case TextureWrap::Repeat:
        break;
    }
    return static_cast<uint32_t>(((i % n) + n) % n);
}

// Texture coordinates past this are treated as this (float precision is long gone there).
constexpr float kMaxCoordinate = 1e6f;

float alphaAt(const TextureImage& image, const Texture& t, int64_t x, int64_t y) {
    const uint32_t xi = wrapIndex(x, image.width, t.wrapS);
    const uint32_t yi = wrapIndex(y, image.height, t.wrapT);
    return image.rgba[(static_cast<size_t>(yi) * image.width + xi) * 4 + 3] / 255.0f;
}

float textureAlpha(const TextureImage& image, const Texture& t, glm::vec2 uv) {
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
        uv = glm::vec2(0.0f);
    uv = glm::clamp(uv, glm::vec2(-kMaxCoordinate), glm::vec2(kMaxCoordinate));
    const float x = uv.x * static_cast<float>(image.width);
    const float y = uv.y * static_cast<float>(image.height);
    if (t.nearest)
        return alphaAt(image, t, static_cast<int64_t>(std::floor(x)),
                       static_cast<int64_t>(std::floor(y)));
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const float ax = fx - x0, ay = fy - y0;
    const auto xi = static_cast<int64_t>(x0), yi = static_cast<int64_t>(y0);
    const float top = (1 - ax) * alphaAt(image, t, xi, yi) + ax * alphaAt(image, t, xi + 1, yi);
    const float bottom =
        (1 - ax) * alphaAt(image, t, xi, yi + 1) + ax * alphaAt(image, t, xi + 1, yi + 1);
    return (1 - ay) * top + ay * bottom;
}

} // namespace

float Scene::coverage(uint32_t material, glm::vec2 uv, float vertexAlpha) const {
    if (material >= materials.size())
        return 1.0f;
    const Material& m = materials[material];
    float alpha = m.baseColor.w * vertexAlpha;
    if (m.baseColorTexture >= 0 && static_cast<size_t>(m.baseColorTexture) < textures.size()) {
        const Texture& t = textures[static_cast<size_t>(m.baseColorTexture)];
        if (t.image < images.size() && !images[t.image].rgba.empty())
            alpha *= textureAlpha(images[t.image], t, uv);
    }
    return alpha;
}

bool Scene::covers(uint32_t material, glm::vec2 uv, float vertexAlpha) const {
    if (material >= materials.size() || !materials[material].alphaTested())
        return true;
    return coverage(material, uv, vertexAlpha) >= materials[material].alphaCutoff;
}

} // namespace penumbra
