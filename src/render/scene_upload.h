#pragma once
// The scene on the device, uploaded once per SceneRenderer (its geometry again per pose): vertices,
// their positions alone (the opaque casters' shadow pass), indices grouped by material (opaque
// first, alpha-tested last) and cut into clusters with bounds for culling, textures, and each
// material's constants.
#include "pass_types.h"
#include "penumbra/scene.h"
#include "render/culling.h"
#include "render/textures.h"
#include "translucent.h"
#include "vk/resources.h"

#include <optional>
#include <vector>

namespace penumbra::render {

// The triangles of one material, contiguous in the index buffer.
struct DrawBatch {
    uint32_t material;
    uint32_t firstIndex, indexCount;
    bool vertexColors; // some vertex's colour is not opaque white (else the G-buffer skips them)
    // The first indices the translucent layer's maps draw (the rest: triangles on the corners of
    // an earlier translucent one, which a shadow ray crosses once, as the truth counts it:
    // docs/translucency.md); indexCount for every other batch.
    uint32_t casterIndexCount = indexCount;
};

// Indices are grouped by material, the alpha-tested materials after the opaque ones and the
// translucent ones (Material::translucent) last, so that the shadow pass draws every opaque
// caster in one call and only the others per material, and the translucent layer leaves the
// translucent ones out of the depth map.
struct GpuScene {
    vk::Buffer vertices, indices;
    vk::Buffer positions;          // the vertices' positions alone: the opaque casters' shadow pass
    std::vector<Cluster> clusters; // of the index buffer, for culling (render/culling.h)
    std::vector<uint32_t> triangleOf; // the scene triangle of each of the index buffer's
    uint32_t indexCount = 0;
    uint32_t opaqueIndexCount = 0; // indices [0, opaqueIndexCount) have no alpha test
    // Indices [translucentFirstIndex, indexCount) are translucent casters' (a batch each).
    uint32_t translucentFirstIndex = 0;
    bool hasTranslucent() const { return translucentFirstIndex < indexCount; }
    std::vector<DrawBatch> batches;
    GpuTextures textures;
    struct Material {
        gpu::MaterialPush constants;
        GpuTextures::Binding texture;             // the 1x1 white texture when it has none
        GpuTextures::Binding transmissionTexture; // linear (UNORM); white when it has none
        bool doubleSided;
        // What its draw into the translucent layer's maps pushes, the view's fields aside.
        gpu::TranslucentCasterPush translucent;
    };
    std::vector<Material> materials; // per Scene::materials
    // Skinned vertices (Scene::skinning): what the frame's `skin` pass reads to place them in
    // `vertices` and `positions` (uploaded holding them in bind space), and whether the next
    // frame runs it (the pose changed since it last ran).
    struct Skin {
        vk::Buffer vertices;   // gpu::SkinVertex[]
        vk::Buffer influences; // gpu::SkinInfluence[]
        vk::Buffer joints;     // this pose's joint matrices (mat4[]), host-visible
        uint32_t count = 0;    // skinned vertices
        bool pending = false;
    };
    std::optional<Skin> skin; // none: nothing is skinned
    // Where the vertices were in the last frame drawn, for the G-buffer's motion vectors
    // (FrameData::motion): the positions buffer that a new pose's upload replaced, or a copy of
    // it made when only skinned vertices moved. `moved`: it holds the last frame drawn and the
    // next frame's vertices may differ from it (none before a pose follows a frame, or when a
    // pose changed the vertex count). `drawn`: a frame drew the positions buffer as it is.
    vk::Buffer previousPositions;
    bool moved = false, drawn = false;
};
GpuScene uploadScene(const vk::Context& ctx, const Scene& scene);
// A material's constants for its translucent caster draws (translucent_caster.glsl).
gpu::TranslucentCasterPush translucentConstants(const Material& material);
// The geometry alone uploaded again (vertices, positions, indices, batches, clusters), the
// textures and materials kept: the scene posed at another time (SceneRenderer::repose). No frame
// may be in flight that reads the old buffers.
void uploadGeometry(const vk::Context& ctx, GpuScene& scene, const Scene& posed);
// The pose `posed` of the scene `uploaded` whose geometry is on the device, when only its skinned
// vertices moved (same triangles, the same unskinned vertices, the same skinned vertices and
// influences): this pose's joint matrices written (and the skinned vertices' bind data where a
// morph target moved them), the clusters' bounds measured again, and the `skin` pass made
// pending. False, and nothing done, for any other change (uploadGeometry then). No frame may be
// in flight.
bool reposeSkinned(const vk::Context& ctx, GpuScene& scene, const Scene& uploaded,
                   const Scene& posed);
// The vertex and positions buffers as the device holds them (the tests' view of the `skin`
// pass's work), `vertexCount` of each, and the previous positions buffer (empty when there is
// none: nothing moved yet).
void readGeometry(const vk::Context& ctx, const GpuScene& scene, size_t vertexCount,
                  std::vector<Vertex>& vertices, std::vector<glm::vec3>& positions,
                  std::vector<glm::vec3>& previous);

} // namespace penumbra::render
