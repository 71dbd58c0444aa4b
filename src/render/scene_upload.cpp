#include "render/scene_upload.h"

#include <algorithm>
#include <span>

namespace penumbra::render {

GpuScene uploadScene(const vk::Context& ctx, const Scene& scene) {
    GpuScene out;
    out.textures = uploadTextures(ctx, scene);
    const size_t materialCount = std::max<size_t>(scene.materials.size(), 1);
    for (size_t m = 0; m < materialCount; ++m) {
        const Material material = m < scene.materials.size() ? scene.materials[m] : Material{};
        out.materials.push_back(
            {.constants = {.baseColor = material.baseColor,
                           .alphaCutoff = material.alphaCutoff,
                           .alphaTest = material.alphaTested() ? 1u : 0u,
                           .hasTexture = material.baseColorTexture >= 0 ? 1u : 0u},
             .texture = out.textures.of(scene, material),
             .doubleSided = material.doubleSided});
    }
    uploadGeometry(ctx, out, scene);
    return out;
}

void uploadGeometry(const vk::Context& ctx, GpuScene& out, const Scene& scene) {
    out.batches.clear();
    out.opaqueIndexCount = 0;
    const size_t materialCount = std::max<size_t>(scene.materials.size(), 1);
    std::vector<std::vector<uint32_t>> byMaterial(materialCount);
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const uint32_t m = scene.vertices[scene.indices[3 * t]].material;
        auto& list = byMaterial[m < materialCount ? m : 0];
        list.insert(list.end(), scene.indices.begin() + static_cast<long>(3 * t),
                    scene.indices.begin() + static_cast<long>(3 * t + 3));
    }
    auto alphaTested = [&](size_t m) {
        return m < scene.materials.size() && scene.materials[m].alphaTested();
    };
    std::vector<uint32_t> indices;
    indices.reserve(scene.indices.size());
    for (const bool tested : {false, true})
        for (size_t m = 0; m < materialCount; ++m) {
            if (alphaTested(m) != tested || byMaterial[m].empty())
                continue;
            const bool coloured =
                std::any_of(byMaterial[m].begin(), byMaterial[m].end(),
                            [&](uint32_t i) { return scene.vertices[i].color != glm::vec4(1.0f); });
            out.batches.push_back({.material = static_cast<uint32_t>(m),
                                   .firstIndex = static_cast<uint32_t>(indices.size()),
                                   .indexCount = static_cast<uint32_t>(byMaterial[m].size()),
                                   .vertexColors = coloured});
            indices.insert(indices.end(), byMaterial[m].begin(), byMaterial[m].end());
            if (!tested)
                out.opaqueIndexCount = static_cast<uint32_t>(indices.size());
        }
    out.vertices = vk::uploadBuffer(ctx, std::as_bytes(std::span(scene.vertices)),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "vertex buffer");
    std::vector<glm::vec3> positions;
    positions.reserve(scene.vertices.size());
    for (const Vertex& v : scene.vertices)
        positions.push_back(v.position);
    out.positions = vk::uploadBuffer(ctx, std::as_bytes(std::span(positions)),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, "position buffer");
    std::vector<uint32_t> batchStarts;
    for (const DrawBatch& batch : out.batches)
        batchStarts.push_back(batch.firstIndex);
    out.clusters = makeClusters(positions, indices, batchStarts);
    out.indices = vk::uploadBuffer(ctx, std::as_bytes(std::span(indices)),
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "index buffer");
    out.indexCount = static_cast<uint32_t>(indices.size());
}

} // namespace penumbra::render
