// Alpha coverage on the CPU, the same test the shadow pass and the G-buffer make on the GPU:
// coverage = baseColor.a x vertex alpha x texture alpha, the texture read at full resolution
// with the sampler's wrap modes and magnification filter (texel centres at (i + 1/2) / size).
// And a translucent surface's transmittance (docs/translucency.md), its textures read the same
// way, colour decoded from sRGB before it is filtered (as an sRGB image view samples it).
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

// `image` read at `uv` as the GPU samples it: nearest, or bilinear between texel centres, each
// texel fetched by `texel(x, y)` (any integers: it wraps them).
template <typename Texel>
auto sampled(const TextureImage& image, const Texture& t, glm::vec2 uv, const Texel& texel) {
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
        uv = glm::vec2(0.0f);
    uv = glm::clamp(uv, glm::vec2(-kMaxCoordinate), glm::vec2(kMaxCoordinate));
    const float x = uv.x * static_cast<float>(image.width);
    const float y = uv.y * static_cast<float>(image.height);
    if (t.nearest)
        return texel(static_cast<int64_t>(std::floor(x)), static_cast<int64_t>(std::floor(y)));
    const float fx = x - 0.5f, fy = y - 0.5f;
    const float x0 = std::floor(fx), y0 = std::floor(fy);
    const float ax = fx - x0, ay = fy - y0;
    const auto xi = static_cast<int64_t>(x0), yi = static_cast<int64_t>(y0);
    const auto top = (1 - ax) * texel(xi, yi) + ax * texel(xi + 1, yi);
    const auto bottom = (1 - ax) * texel(xi, yi + 1) + ax * texel(xi + 1, yi + 1);
    return (1 - ay) * top + ay * bottom;
}

float textureAlpha(const TextureImage& image, const Texture& t, glm::vec2 uv) {
    return sampled(image, t, uv, [&](int64_t x, int64_t y) { return alphaAt(image, t, x, y); });
}

// One texel's linear RGBA: colour decoded from sRGB where `srgb` (glTF's base colour), else as
// stored (the transmission texture); alpha always as stored.
glm::vec4 texelAt(const TextureImage& image, const Texture& t, int64_t x, int64_t y, bool srgb) {
    const uint32_t xi = wrapIndex(x, image.width, t.wrapS);
    const uint32_t yi = wrapIndex(y, image.height, t.wrapT);
    const uint8_t* p = &image.rgba[(static_cast<size_t>(yi) * image.width + xi) * 4];
    glm::vec4 c(p[0], p[1], p[2], p[3]);
    c /= 255.0f;
    if (srgb)
        for (int i = 0; i < 3; ++i)
            c[i] = c[i] <= 0.04045f ? c[i] / 12.92f : std::pow((c[i] + 0.055f) / 1.055f, 2.4f);
    return c;
}

glm::vec4 textureColour(const TextureImage& image, const Texture& t, glm::vec2 uv, bool srgb) {
    return sampled(image, t, uv,
                   [&](int64_t x, int64_t y) { return texelAt(image, t, x, y, srgb); });
}

// The image a material's texture index reads, or null (none, or not decoded).
const TextureImage* imageOf(const Scene& scene, int32_t texture) {
    if (texture < 0 || static_cast<size_t>(texture) >= scene.textures.size())
        return nullptr;
    const Texture& t = scene.textures[static_cast<size_t>(texture)];
    if (t.image >= scene.images.size() || scene.images[t.image].rgba.empty())
        return nullptr;
    return &scene.images[t.image];
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

glm::vec3 Scene::transmittance(uint32_t material, glm::vec2 uv, glm::vec4 vertexColor) const {
    if (material >= materials.size())
        return glm::vec3(0.0f);
    const Material& m = materials[material];
    float covered = 1.0f; // Opaque, and Mask where it covers
    if (m.alphaMode == AlphaMode::Mask && !covers(material, uv, vertexColor.w))
        return glm::vec3(1.0f);
    if (m.alphaMode == AlphaMode::Blend)
        covered = std::clamp(coverage(material, uv, vertexColor.w), 0.0f, 1.0f);
    glm::vec3 through(0.0f);
    if (m.transmission > 0.0f) {
        float fraction = m.transmission;
        if (const TextureImage* image = imageOf(*this, m.transmissionTexture))
            fraction *= textureColour(*image, textures[size_t(m.transmissionTexture)], uv, false).x;
        glm::vec3 tint = glm::vec3(m.baseColor) * glm::vec3(vertexColor);
        if (const TextureImage* image = imageOf(*this, m.baseColorTexture))
            tint *=
                glm::vec3(textureColour(*image, textures[size_t(m.baseColorTexture)], uv, true));
        through = glm::clamp(fraction * tint, 0.0f, 1.0f);
        if (m.thickness > 0.0f) {
            // A closed volume, crossed in and out: each face keeps the square root of the tint
            // and half the path's attenuation (Beer-Lambert over the thickness).
            glm::vec3 perUnit(0.0f);
            if (std::isfinite(m.attenuationDistance) && m.attenuationDistance > 0.0f)
                perUnit =
                    -glm::log(glm::clamp(m.attenuationColor, 0.0f, 1.0f)) / m.attenuationDistance;
            through = glm::sqrt(through) * glm::exp(-perUnit * (0.5f * m.thickness));
        }
    }
    return (1.0f - covered) + covered * through;
}

bool Scene::hasTranslucentCasters() const {
    for (size_t t = 0; t < triangleCount(); ++t) {
        const uint32_t m = vertices[indices[3 * t]].material;
        if (m < materials.size() && materials[m].translucent())
            return true;
    }
    return false;
}

} // namespace penumbra
