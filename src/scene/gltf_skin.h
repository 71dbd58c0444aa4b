#pragma once
// glTF skins (the specification's section 3.7.3) read for Scene::skinning: each joint's matrix is
// its node's posed world transform times its inverse bind matrix, and a vertex moves by the
// weighted sum of its joints' matrices over every JOINTS_n/WEIGHTS_n set (placed on the host by
// placeSkinnedVertices, on the GPU by the frame's `skin` pass). The skinned mesh's own node
// transform is ignored, as the specification says.
#include "penumbra/scene.h"
#include "scene/gltf_animation.h"

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include <filesystem>
#include <vector>

namespace penumbra::gltf {

struct Skin {
    std::vector<size_t> joints;         // node indices
    std::vector<glm::mat4> inverseBind; // one per joint (identity without the accessor)
};

// Every skin, checked: joints in range and each once, the skeleton in range, the inverse bind
// matrices MAT4 floats, at least one per joint. InputError(file, "skins[s]...: what").
std::vector<Skin> readSkins(const std::filesystem::path& file, const tinygltf::Model& model);

// Every node's world transform with `poses`: roots (nodes no node lists as a child) at the
// identity. (validateModel has refused cycles and second parents.)
std::vector<glm::mat4> nodeWorlds(const tinygltf::Model& model, const std::vector<NodePose>& poses);

// Each joint's matrix in the pose of `worlds`: its node's world transform times its inverse bind
// matrix.
std::vector<glm::mat4> jointMatrices(const Skin& skin, const std::vector<glm::mat4>& worlds);

// Every vertex's influences: vertex v's are influences[starts[v], starts[v + 1]), each a joint of
// the skin (an index into Skin::joints) and its weight over the vertex's sum (weights of 0 left
// out).
struct PrimitiveInfluences {
    std::vector<uint32_t> starts; // one per vertex, and the end
    std::vector<SkinInfluence> influences;
};

// The influences of the vertices of primitive `prim` (at JSON path `path`) of node `node`, which
// has `skin`, over every JOINTS_n/WEIGHTS_n set. InputError naming the attribute: joints that are
// not VEC4 unsigned bytes or shorts, weights that are not VEC4 floats or normalized unsigned bytes
// or shorts, a joint past the skin's joints, a negative weight, a vertex whose weights sum to 0
// (summed in double: weights near the float's limit would overflow a float sum), a skinned
// primitive without JOINTS_0 and WEIGHTS_0.
PrimitiveInfluences skinInfluences(const std::filesystem::path& file, const tinygltf::Model& model,
                                   const tinygltf::Primitive& prim, const std::string& path,
                                   size_t node, const Skin& skin);

} // namespace penumbra::gltf
