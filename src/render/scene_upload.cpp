#include "render/scene_upload.h"

#include "skinning.h"
#include "translucent.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <set>
#include <span>
#include <tuple>

namespace penumbra::render {

// The skin pass writes a Vertex as VERTEX_FLOATS floats, its position and normal where these say.
static_assert(sizeof(Vertex) == 4 * VERTEX_FLOATS &&
              offsetof(Vertex, position) == 4 * VERTEX_POSITION_FLOAT &&
              offsetof(Vertex, normal) == 4 * VERTEX_NORMAL_FLOAT);
// Scene::skinning's influences go up as they are: gpu::SkinInfluence's layout.
static_assert(sizeof(SkinInfluence) == sizeof(gpu::SkinInfluence) &&
              offsetof(SkinInfluence, joint) == offsetof(gpu::SkinInfluence, joint) &&
              offsetof(SkinInfluence, weight) == offsetof(gpu::SkinInfluence, weight));

namespace {

// A positions buffer as the motion vectors' previous positions: read by the G-buffer's vertex
// shader, written by a copy (GpuScene::previousPositions).
constexpr VkBufferUsageFlags kPreviousUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
    VK_BUFFER_USAGE_TRANSFER_SRC_BIT; // read back by the tests

// The index buffer's order: grouped by material, the opaque ones first, then the alpha-tested
// ones, the translucent ones last.
struct IndexLayout {
    std::vector<DrawBatch> batches;
    std::vector<uint32_t> indices;
    std::vector<uint32_t> triangles; // the scene triangle of each of `indices`' triangles
    uint32_t opaqueIndexCount = 0, translucentFirstIndex = 0;
};

enum class Group { Opaque, AlphaTested, Translucent };

IndexLayout layoutIndices(const Scene& scene) {
    IndexLayout out;
    const size_t materialCount = std::max<size_t>(scene.materials.size(), 1);
    std::vector<std::vector<uint32_t>> byMaterial(materialCount), trianglesOf(materialCount);
    for (size_t t = 0; t < scene.triangleCount(); ++t) {
        const uint32_t m = scene.vertices[scene.indices[3 * t]].material;
        auto& list = byMaterial[m < materialCount ? m : 0];
        list.insert(list.end(), scene.indices.begin() + static_cast<long>(3 * t),
                    scene.indices.begin() + static_cast<long>(3 * t + 3));
        trianglesOf[m < materialCount ? m : 0].push_back(static_cast<uint32_t>(t));
    }
    auto groupOf = [&](size_t m) {
        if (m >= scene.materials.size())
            return Group::Opaque;
        const Material& material = scene.materials[m];
        return material.translucent()   ? Group::Translucent
               : material.alphaTested() ? Group::AlphaTested
                                        : Group::Opaque;
    };
    // A translucent triangle on the corners of an earlier one (a leaf modelled as two triangles
    // back to back, a film on glass) goes to the end of its batch, which the layer's maps leave
    // out: the truth's shadow ray crosses the two once.
    std::set<std::array<float, 9>> cornersSeen;
    auto splitRepeats = [&](size_t m) {
        std::vector<uint32_t> first, repeats, firstTriangles, repeatTriangles;
        for (size_t k = 0; k < trianglesOf[m].size(); ++k) {
            std::array<glm::vec3, 3> corners{};
            for (size_t c = 0; c < 3; ++c)
                corners[c] = scene.vertices[byMaterial[m][3 * k + c]].position;
            std::sort(corners.begin(), corners.end(), [](const glm::vec3& a, const glm::vec3& b) {
                return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
            });
            std::array<float, 9> key{};
            for (size_t c = 0; c < 3; ++c)
                for (int axis = 0; axis < 3; ++axis)
                    key[3 * c + size_t(axis)] = corners[c][axis];
            const bool repeat = !cornersSeen.insert(key).second;
            auto& indices = repeat ? repeats : first;
            indices.insert(indices.end(), byMaterial[m].begin() + static_cast<long>(3 * k),
                           byMaterial[m].begin() + static_cast<long>(3 * k + 3));
            (repeat ? repeatTriangles : firstTriangles).push_back(trianglesOf[m][k]);
        }
        const auto casterCount = static_cast<uint32_t>(first.size());
        first.insert(first.end(), repeats.begin(), repeats.end());
        firstTriangles.insert(firstTriangles.end(), repeatTriangles.begin(), repeatTriangles.end());
        byMaterial[m] = std::move(first);
        trianglesOf[m] = std::move(firstTriangles);
        return casterCount;
    };
    out.indices.reserve(scene.indices.size());
    for (const Group group : {Group::Opaque, Group::AlphaTested, Group::Translucent}) {
        if (group == Group::Translucent)
            out.translucentFirstIndex = static_cast<uint32_t>(out.indices.size());
        for (size_t m = 0; m < materialCount; ++m) {
            if (groupOf(m) != group || byMaterial[m].empty())
                continue;
            const auto count = static_cast<uint32_t>(byMaterial[m].size());
            const uint32_t casterCount = group == Group::Translucent ? splitRepeats(m) : count;
            const bool coloured =
                std::any_of(byMaterial[m].begin(), byMaterial[m].end(),
                            [&](uint32_t i) { return scene.vertices[i].color != glm::vec4(1.0f); });
            out.batches.push_back({.material = static_cast<uint32_t>(m),
                                   .firstIndex = static_cast<uint32_t>(out.indices.size()),
                                   .indexCount = count,
                                   .vertexColors = coloured,
                                   .casterIndexCount = casterCount});
            out.indices.insert(out.indices.end(), byMaterial[m].begin(), byMaterial[m].end());
            out.triangles.insert(out.triangles.end(), trianglesOf[m].begin(), trianglesOf[m].end());
            if (group == Group::Opaque)
                out.opaqueIndexCount = static_cast<uint32_t>(out.indices.size());
        }
    }
    return out;
}

std::vector<glm::vec3> positionsOf(std::span<const Vertex> vertices) {
    std::vector<glm::vec3> positions;
    positions.reserve(vertices.size());
    for (const Vertex& v : vertices)
        positions.push_back(v.position);
    return positions;
}

// Where clusters must start: each batch, and the repeated triangles a translucent batch's draws
// into the layer's maps leave out (no cluster straddles them).
std::vector<uint32_t> batchStarts(const std::vector<DrawBatch>& batches) {
    std::vector<uint32_t> starts;
    for (const DrawBatch& batch : batches) {
        starts.push_back(batch.firstIndex);
        if (batch.casterIndexCount > 0 && batch.casterIndexCount < batch.indexCount)
            starts.push_back(batch.firstIndex + batch.casterIndexCount);
    }
    return starts;
}

std::vector<gpu::SkinVertex> skinVertices(const Skinning& skinning) {
    std::vector<gpu::SkinVertex> out;
    out.reserve(skinning.vertices.size());
    for (const SkinnedVertex& s : skinning.vertices)
        out.push_back({.position = s.position,
                       .vertex = s.vertex,
                       .normal = s.normal,
                       .firstInfluence = s.firstInfluence,
                       .influenceCount = s.influenceCount});
    return out;
}

void writeJoints(GpuScene::Skin& skin, const Skinning& skinning) {
    std::memcpy(skin.joints.mapped, skinning.joints.data(),
                skinning.joints.size() * sizeof(glm::mat4));
}

bool sameBindData(const SkinnedVertex& a, const SkinnedVertex& b) {
    return a.position == b.position && a.normal == b.normal;
}

} // namespace

gpu::TranslucentCasterPush translucentConstants(const Material& m) {
    uint32_t flags = m.baseColorTexture >= 0 ? TRANSLUCENT_TEXTURE : 0u;
    if (m.alphaMode == AlphaMode::Blend)
        flags |= TRANSLUCENT_BLEND;
    if (m.alphaMode == AlphaMode::Mask)
        flags |= TRANSLUCENT_MASK;
    // Scene::transmittance's volume: each face keeps the square root of the tint and half the
    // path's Beer-Lambert attenuation over the thickness.
    glm::vec3 perUnit(0.0f);
    if (m.thickness > 0.0f) {
        flags |= TRANSLUCENT_VOLUME;
        if (std::isfinite(m.attenuationDistance) && m.attenuationDistance > 0.0f)
            perUnit = -glm::log(glm::clamp(m.attenuationColor, 0.0f, 1.0f)) / m.attenuationDistance;
    }
    return {.bias = {0.0f, m.alphaCutoff, m.transmission, 0.0f},
            .baseColor = m.baseColor,
            .attenuation = glm::vec4(glm::exp(-perUnit * (0.5f * m.thickness)), 0.0f),
            .flags = {flags, 0u, 0u, 0u}};
}

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
             .transmissionTexture = out.textures.transmissionOf(scene, material),
             .doubleSided = material.doubleSided,
             .translucent = translucentConstants(material)});
    }
    uploadGeometry(ctx, out, scene);
    return out;
}

void uploadGeometry(const vk::Context& ctx, GpuScene& out, const Scene& scene) {
    IndexLayout layout = layoutIndices(scene);
    out.batches = std::move(layout.batches);
    out.opaqueIndexCount = layout.opaqueIndexCount;
    out.translucentFirstIndex = layout.translucentFirstIndex;
    out.clusters =
        makeClusters(positionsOf(scene.vertices), layout.indices, batchStarts(out.batches));
    out.triangleOf = std::move(layout.triangles);
    const Skinning& skinning = scene.skinning;
    // Skinned vertices go up in bind space: the `skin` pass places them, in the first frame.
    std::vector<Vertex> vertices = scene.vertices;
    for (const SkinnedVertex& s : skinning.vertices) {
        vertices[s.vertex].position = s.position;
        vertices[s.vertex].normal = s.normal;
    }
    VkBufferUsageFlags written = VK_BUFFER_USAGE_TRANSFER_SRC_BIT; // read back by the tests
    if (!skinning.empty())
        written |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT; // the skin pass writes them
    out.vertices = vk::uploadBuffer(ctx, std::as_bytes(std::span(vertices)),
                                    VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | written, "vertex buffer");
    const std::vector<glm::vec3> positions = positionsOf(vertices);
    // The positions drawn last stay for the motion vectors (where no frame drew these, the
    // previous positions already hold the last frame drawn, or nothing).
    if (out.drawn) {
        out.previousPositions = std::move(out.positions);
        out.moved = true;
    }
    out.drawn = false;
    if (out.previousPositions.size != positions.size() * sizeof(glm::vec3)) {
        out.previousPositions = {}; // another vertex count: nothing says where they were
        out.moved = false;
    }
    // A positions buffer becomes the previous one (read by the G-buffer, copied into).
    out.positions = vk::uploadBuffer(ctx, std::as_bytes(std::span(positions)),
                                     VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | kPreviousUsage | written,
                                     "position buffer");
    out.indices = vk::uploadBuffer(ctx, std::as_bytes(std::span(layout.indices)),
                                   VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "index buffer");
    out.indexCount = static_cast<uint32_t>(layout.indices.size());
    out.skin.reset();
    if (skinning.empty())
        return;
    GpuScene::Skin& skin = out.skin.emplace();
    const std::vector<gpu::SkinVertex> records = skinVertices(skinning);
    skin.vertices = vk::uploadBuffer(ctx, std::as_bytes(std::span(records)),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "skinned vertices");
    skin.influences = vk::uploadBuffer(ctx, std::as_bytes(std::span(skinning.influences)),
                                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "skin influences");
    skin.joints = vk::createBuffer(ctx, skinning.joints.size() * sizeof(glm::mat4),
                                   VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, vk::MemoryUse::Upload,
                                   "joint matrices");
    writeJoints(skin, skinning);
    skin.count = static_cast<uint32_t>(records.size());
    skin.pending = true;
}

bool reposeSkinned(const vk::Context& ctx, GpuScene& out, const Scene& uploaded,
                   const Scene& posed) {
    const Skinning &was = uploaded.skinning, &now = posed.skinning;
    if (!out.skin || now.empty() || posed.indices != uploaded.indices ||
        posed.vertices.size() != uploaded.vertices.size() ||
        now.vertices.size() != was.vertices.size() || now.joints.size() != was.joints.size() ||
        now.influences.size() != was.influences.size())
        return false;
    std::vector<bool> skinned(posed.vertices.size(), false);
    for (size_t s = 0; s < now.vertices.size(); ++s) {
        const SkinnedVertex &a = now.vertices[s], &b = was.vertices[s];
        if (a.vertex != b.vertex || a.firstInfluence != b.firstInfluence ||
            a.influenceCount != b.influenceCount || a.vertex >= skinned.size())
            return false;
        skinned[a.vertex] = true;
    }
    for (size_t k = 0; k < now.influences.size(); ++k)
        if (now.influences[k].joint != was.influences[k].joint ||
            now.influences[k].weight != was.influences[k].weight)
            return false;
    for (size_t v = 0; v < posed.vertices.size(); ++v)
        if (!skinned[v] && std::memcmp(&posed.vertices[v], &uploaded.vertices[v], sizeof(Vertex)))
            return false;
    for (size_t s = 0; s < now.vertices.size(); ++s)
        if (!sameBindData(now.vertices[s], was.vertices[s])) { // a morph target moved them
            const std::vector<gpu::SkinVertex> records = skinVertices(now);
            out.skin->vertices =
                vk::uploadBuffer(ctx, std::as_bytes(std::span(records)),
                                 VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "skinned vertices");
            break;
        }
    writeJoints(*out.skin, now);
    // Culling reads the clusters' bounds: this pose's, from the host's placement.
    IndexLayout layout = layoutIndices(posed);
    out.clusters =
        makeClusters(positionsOf(posed.vertices), layout.indices, batchStarts(layout.batches));
    out.triangleOf = std::move(layout.triangles);
    out.skin->pending = true;
    // The motion vectors' previous positions: where the last frame drew the vertices, copied
    // before the next `skin` pass moves them (where no frame drew the buffer as it is, the
    // previous positions already hold the last frame drawn, or nothing).
    if (out.drawn) {
        if (out.previousPositions.size != out.positions.size)
            out.previousPositions =
                vk::createBuffer(ctx, out.positions.size, kPreviousUsage,
                                 vk::MemoryUse::DeviceLocal, "previous positions");
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            const VkBufferCopy all{.size = out.positions.size};
            vkCmdCopyBuffer(cmd, out.positions.get(), out.previousPositions.get(), 1, &all);
        });
        out.moved = true;
    }
    out.drawn = false;
    return true;
}

void readGeometry(const vk::Context& ctx, const GpuScene& scene, size_t vertexCount,
                  std::vector<Vertex>& vertices, std::vector<glm::vec3>& positions,
                  std::vector<glm::vec3>& previous) {
    vertices.resize(vertexCount);
    positions.resize(vertexCount);
    const bool moved = scene.previousPositions.get() != VK_NULL_HANDLE;
    previous.resize(moved ? vertexCount : 0);
    const VkDeviceSize vertexBytes = vertexCount * sizeof(Vertex),
                       positionBytes = vertexCount * sizeof(glm::vec3);
    vk::Buffer readback =
        vk::createBuffer(ctx, vertexBytes + 2 * positionBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         vk::MemoryUse::Readback, "geometry readback");
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        const VkBufferCopy vertexRegion{.size = vertexBytes},
            positionRegion{.dstOffset = vertexBytes, .size = positionBytes},
            previousRegion{.dstOffset = vertexBytes + positionBytes, .size = positionBytes};
        vkCmdCopyBuffer(cmd, scene.vertices.get(), readback.get(), 1, &vertexRegion);
        vkCmdCopyBuffer(cmd, scene.positions.get(), readback.get(), 1, &positionRegion);
        if (moved)
            vkCmdCopyBuffer(cmd, scene.previousPositions.get(), readback.get(), 1, &previousRegion);
    });
    const auto* bytes = static_cast<const std::byte*>(readback.mapped);
    std::memcpy(vertices.data(), bytes, vertexBytes);
    std::memcpy(positions.data(), bytes + vertexBytes, positionBytes);
    if (moved)
        std::memcpy(previous.data(), bytes + vertexBytes + positionBytes, positionBytes);
}

} // namespace penumbra::render
