// Linear blend skinning on the GPU (skin.comp, the frame's `skin` pass): the records the host
// uploads (src/render/scene_upload.cpp) and the vertex buffer's layout the pass writes into,
// compiled as GLSL and as C++ with static_asserts on their layout. The host's placement of the
// same vertices, which the GPU's is checked against, is placeSkinnedVertices (src/scene).
// clang-format off
#ifndef PENUMBRA_SKINNING_H
#define PENUMBRA_SKINNING_H
#include "shared_prelude.h"

#define SKIN_BLOCK 64u           // invocations per workgroup, one skinned vertex each
// A vertex of the vertex buffer (penumbra::Vertex) as floats: its size and where its position
// and normal start. The pass writes them there, and the positions buffer's 3 floats a vertex.
#define VERTEX_FLOATS 13u
#define VERTEX_POSITION_FLOAT 0u
#define VERTEX_NORMAL_FLOAT 3u

PENUMBRA_GPU_BEGIN

struct SkinVertex {        // one skinned vertex: where it is in bind space, where it goes
    vec3 position;         // bind space
    uint vertex;           // its index in the vertex and positions buffers
    vec3 normal;           // bind space, any length
    uint firstInfluence;   // into the influences
    uint influenceCount;
    uint pad0, pad1, pad2;
};

struct SkinInfluence {
    uint joint;            // into the joint matrices
    float weight;          // a vertex's sum to 1
};

struct SkinPush {
    uint first;            // the first skinned vertex of this dispatch
    uint count;            // every skinned vertex
    uint pad0, pad1;
};

PENUMBRA_GPU_END

#ifdef __cplusplus
namespace penumbra::gpu {
static_assert(sizeof(SkinVertex) == 48 && offsetof(SkinVertex, vertex) == 12 &&
              offsetof(SkinVertex, normal) == 16 && offsetof(SkinVertex, firstInfluence) == 28 &&
              offsetof(SkinVertex, influenceCount) == 32);
static_assert(sizeof(SkinInfluence) == 8 && offsetof(SkinInfluence, weight) == 4);
static_assert(sizeof(SkinPush) == 16);
} // namespace penumbra::gpu
#endif

#endif
// clang-format on
