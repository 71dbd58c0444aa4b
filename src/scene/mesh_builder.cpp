#include "scene/mesh_builder.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace penumbra {

uint32_t MeshBuilder::material(const std::string& name, const glm::vec3& linearColor) {
    mScene.materials.push_back({.name = name, .baseColor = glm::vec4(linearColor, 1.0f)});
    return static_cast<uint32_t>(mScene.materials.size() - 1);
}

uint32_t MeshBuilder::texturedMaterial(const std::string& name, TextureImage image,
                                       const Texture& sampling, AlphaMode mode, float alphaCutoff) {
    Texture texture = sampling;
    texture.image = static_cast<uint32_t>(mScene.images.size());
    mScene.images.push_back(std::move(image));
    mScene.materials.push_back({.name = name,
                                .baseColor = glm::vec4(1.0f),
                                .baseColorTexture = static_cast<int32_t>(mScene.textures.size()),
                                .alphaMode = mode,
                                .alphaCutoff = alphaCutoff});
    mScene.textures.push_back(texture);
    return static_cast<uint32_t>(mScene.materials.size() - 1);
}

uint32_t MeshBuilder::vertex(const glm::vec3& p, const glm::vec3& n, uint32_t material,
                             glm::vec2 uv) {
    mScene.vertices.push_back(
        {.position = p, .normal = glm::normalize(n), .material = material, .uv = uv});
    return static_cast<uint32_t>(mScene.vertices.size() - 1);
}

void MeshBuilder::quad(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                       const glm::vec3& d, uint32_t material, glm::vec2 uvScale) {
    const glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
    const uint32_t i0 = vertex(a, n, material, {0.0f, uvScale.y});
    const uint32_t i1 = vertex(b, n, material, uvScale);
    const uint32_t i2 = vertex(c, n, material, {uvScale.x, 0.0f});
    const uint32_t i3 = vertex(d, n, material, {0.0f, 0.0f});
    mScene.indices.insert(mScene.indices.end(), {i0, i1, i2, i0, i2, i3});
}

void MeshBuilder::box(const glm::mat4& transform, uint32_t material) {
    auto at = [&](float x, float y, float z) {
        return glm::vec3(transform * glm::vec4(x - 0.5f, y - 0.5f, z - 0.5f, 1.0f));
    };
    // Each face: four unit-cube corners, counter-clockwise seen from outside.
    const float faces[6][4][3] = {
        {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}, {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}},
        {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}}, {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}, {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}};
    for (const auto& f : faces)
        quad(at(f[0][0], f[0][1], f[0][2]), at(f[1][0], f[1][1], f[1][2]),
             at(f[2][0], f[2][1], f[2][2]), at(f[3][0], f[3][1], f[3][2]), material);
}

void MeshBuilder::beam(const glm::vec3& from, const glm::vec3& to, float thickness,
                       uint32_t material) {
    const glm::vec3 axis = to - from;
    const float length = glm::length(axis);
    const glm::vec3 y = axis / length;
    const glm::vec3 helper = std::abs(y.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1);
    const glm::vec3 x = glm::normalize(glm::cross(helper, y));
    const glm::vec3 z = glm::cross(x, y);
    glm::mat4 m(glm::vec4(x * thickness, 0), glm::vec4(y * length, 0), glm::vec4(z * thickness, 0),
                glm::vec4(0.5f * (from + to), 1));
    box(m, material);
}

void MeshBuilder::sphere(const glm::vec3& center, float radius, uint32_t material, uint32_t slices,
                         uint32_t stacks) {
    const uint32_t base = static_cast<uint32_t>(mScene.vertices.size());
    const float pi = 3.14159265358979f;
    for (uint32_t i = 0; i <= stacks; ++i) {
        const float theta = pi * static_cast<float>(i) / static_cast<float>(stacks);
        for (uint32_t j = 0; j <= slices; ++j) {
            const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
            const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                              -std::sin(theta) * std::sin(phi));
            vertex(center + radius * n, n, material);
        }
    }
    for (uint32_t i = 0; i < stacks; ++i)
        for (uint32_t j = 0; j < slices; ++j) {
            const uint32_t a = base + i * (slices + 1) + j, b = a + slices + 1;
            if (i != 0)
                mScene.indices.insert(mScene.indices.end(), {a, b, a + 1});
            if (i + 1 != stacks)
                mScene.indices.insert(mScene.indices.end(), {a + 1, b, b + 1});
        }
}

namespace {

// Two unit vectors completing `axis` (unit) to an orthonormal basis.
void basisAround(const glm::vec3& axis, glm::vec3& u, glm::vec3& v) {
    const glm::vec3 helper =
        std::abs(axis.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    u = glm::normalize(glm::cross(helper, axis));
    v = glm::cross(axis, u);
}

} // namespace

void MeshBuilder::tube(const glm::vec3& from, const glm::vec3& to, float radius, uint32_t material,
                       uint32_t slices) {
    const glm::vec3 axis = glm::normalize(to - from);
    glm::vec3 u, v;
    basisAround(axis, u, v);
    const float pi = 3.14159265358979f;
    const uint32_t base = static_cast<uint32_t>(mScene.vertices.size());
    for (uint32_t j = 0; j <= slices; ++j) {
        const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
        const glm::vec3 n = std::cos(phi) * u + std::sin(phi) * v;
        vertex(from + radius * n, n, material);
        vertex(to + radius * n, n, material);
    }
    for (uint32_t j = 0; j < slices; ++j) {
        const uint32_t a = base + 2 * j; // a: from, a + 1: to; a + 2, a + 3 the next slice's
        mScene.indices.insert(mScene.indices.end(), {a, a + 2, a + 1, a + 1, a + 2, a + 3});
    }
    for (int end = 0; end < 2; ++end) { // flat caps, fanned about their centres
        const glm::vec3 centre = end == 0 ? from : to, n = end == 0 ? -axis : axis;
        const uint32_t hub = static_cast<uint32_t>(mScene.vertices.size());
        vertex(centre, n, material);
        for (uint32_t j = 0; j <= slices; ++j) {
            const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
            vertex(centre + radius * (std::cos(phi) * u + std::sin(phi) * v), n, material);
        }
        for (uint32_t j = 0; j < slices; ++j) {
            const uint32_t a = hub + 1 + j;
            if (end == 0)
                mScene.indices.insert(mScene.indices.end(), {hub, a + 1, a});
            else
                mScene.indices.insert(mScene.indices.end(), {hub, a, a + 1});
        }
    }
}

void MeshBuilder::torus(const glm::vec3& center, const glm::vec3& axis, float major, float minor,
                        uint32_t material, uint32_t segments, uint32_t sides) {
    glm::vec3 u, v;
    basisAround(glm::normalize(axis), u, v);
    const glm::vec3 w = glm::normalize(axis);
    const float pi = 3.14159265358979f;
    const uint32_t base = static_cast<uint32_t>(mScene.vertices.size());
    for (uint32_t i = 0; i <= segments; ++i) {
        const float theta = 2.0f * pi * static_cast<float>(i) / static_cast<float>(segments);
        const glm::vec3 radial = std::cos(theta) * u + std::sin(theta) * v;
        for (uint32_t j = 0; j <= sides; ++j) {
            const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(sides);
            const glm::vec3 n = std::cos(phi) * radial + std::sin(phi) * w;
            vertex(center + major * radial + minor * n, n, material);
        }
    }
    for (uint32_t i = 0; i < segments; ++i)
        for (uint32_t j = 0; j < sides; ++j) {
            const uint32_t a = base + i * (sides + 1) + j, b = a + sides + 1;
            mScene.indices.insert(mScene.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
        }
}

} // namespace penumbra
