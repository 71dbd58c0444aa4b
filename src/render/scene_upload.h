#pragma once
// The scene on the device, uploaded once per SceneRenderer (its geometry again per pose): vertices,
// their positions alone (the opaque casters' shadow pass), indices grouped by material (opaque
// first, alpha-tested last) and cut into clusters with bounds for culling, textures, and each
// material's constants.
#include "pass_types.h"
#include "penumbra/scene.h"
#include "render/culling.h"
#include "render/textures.h"
#include "vk/resources.h"

#include <vector>

namespace penumbra::render {

// The triangles of one material, contiguous in the index buffer.
struct DrawBatch {
    uint32_t material;
    uint32_t firstIndex, indexCount;
    bool vertexColors; // some vertex's colour is not opaque white (else the G-buffer skips them)
};

// Indices are grouped by material, the alpha-tested materials last, so that the shadow pass
// draws every opaque caster in one call and only the alpha-tested ones per material.
struct GpuScene {
    vk::Buffer vertices, indices;
    vk::Buffer positions;          // the vertices' positions alone: the opaque casters' shadow pass
    std::vector<Cluster> clusters; // of the index buffer, for culling (render/culling.h)
    uint32_t indexCount = 0;
    uint32_t opaqueIndexCount = 0; // indices [0, opaqueIndexCount) have no alpha test
    std::vector<DrawBatch> batches;
    GpuTextures textures;
    struct Material {
        gpu::MaterialPush constants;
        GpuTextures::Binding texture; // the 1x1 white texture when it has none
        bool doubleSided;
    };
    std::vector<Material> materials; // per Scene::materials
};
GpuScene uploadScene(const vk::Context& ctx, const Scene& scene);
// The geometry alone uploaded again (vertices, positions, indices, batches, clusters), the
// textures and materials kept: the scene posed at another time (SceneRenderer::repose). No frame
// may be in flight that reads the old buffers.
void uploadGeometry(const vk::Context& ctx, GpuScene& scene, const Scene& posed);

} // namespace penumbra::render
